/// run_isolated(): work in a child process; its exceptions and its crashes come back as errors.

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include <stiffsoft/meshing/isolated_call.hpp>

namespace {

std::string error_of(const std::function<void()>& work) {
  try {
    stiffsoft::run_isolated("file.msh", "the reader", work);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

TEST(RunIsolated, ReturnsWhenTheWorkReturnsAndItsFilesStay) {
  const auto file = std::filesystem::temp_directory_path() / ("isolated_" + std::to_string(::getpid()) + ".txt");
  EXPECT_EQ(error_of([&] { std::ofstream(file) << "from the child"; }), "");
  std::string text;
  std::getline(std::ifstream(file), text);
  EXPECT_EQ(text, "from the child");
  std::filesystem::remove(file);
}

TEST(RunIsolated, PassesAnExceptionsMessageOn) {
  EXPECT_EQ(error_of([] { throw std::runtime_error("file.msh: no tetrahedra"); }), "file.msh: no tetrahedra");
}

TEST(RunIsolated, TurnsACrashIntoAnErrorNamingTheFile) {
  const std::string error = error_of([] { std::abort(); });
  EXPECT_NE(error.find("file.msh: the reader crashed"), std::string::npos) << error;
  EXPECT_NE(error.find("malformed"), std::string::npos) << error;
}

TEST(RunIsolated, TurnsASegmentationFaultIntoAnError) {
  // A sanitizer catches the signal itself and exits with its own status: "crashed" either way.
  const std::string error = error_of([] { std::raise(SIGSEGV); });
  EXPECT_NE(error.find("file.msh: the reader crashed"), std::string::npos) << error;
}

}  // namespace
