#pragma once
/// @file Turns VTK's error events into a message the caller can throw (private to io/).

#include <vtkCommand.h>

#include <cctype>
#include <string>

namespace stiffsoft {

/// Collects VTK's error messages so they become exceptions instead of text on stderr
/// (vtkErrorMacro only prints when the object has no ErrorEvent observer).
class VtkErrorCatcher : public vtkCommand {
 public:
  /// VTK's factory (vtkNew<VtkErrorCatcher>).
  static VtkErrorCatcher* New() { return new VtkErrorCatcher; }
  /// Keeps the first error's text.
  void Execute(vtkObject*, unsigned long, void* call_data) override {
    // The first error is the cause; later ones are the pipeline reporting the failure upwards.
    if (failed || call_data == nullptr) {
      failed = true;
      return;
    }
    failed = true;
    // VTK's text is "ERROR: In <source>, line N\n<class> (0x..): <what>\n"; keep <what>.
    message = static_cast<const char*>(call_data);
    const std::size_t what = message.find("): ");
    if (what != std::string::npos) message.erase(0, what + 3);
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) {
      message.pop_back();
    }
  }
  bool failed = false;  ///< an error was reported
  std::string message;  ///< the first error's text, without VTK's source-location prefix
};

}  // namespace stiffsoft
