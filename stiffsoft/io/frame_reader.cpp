#include <stiffsoft/io/frame_reader.hpp>

#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <stiffsoft/io/vtk_error_catcher.hpp>

namespace stiffsoft {

namespace {


std::runtime_error file_error(const std::filesystem::path& file, const std::string& what) {
  return std::runtime_error("cannot read '" + file.string() + "': " + what);
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "missing or unreadable file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw file_error(file, "I/O error while reading");
  return text.str();
}

std::string xml_unescape(const std::string& s) {
  static const std::pair<const char*, char> entities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    bool replaced = false;
    if (s[i] == '&') {
      for (const auto& [entity, c] : entities) {
        if (s.compare(i, std::char_traits<char>::length(entity), entity) == 0) {
          out += c;
          i += std::char_traits<char>::length(entity);
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += s[i++];
  }
  return out;
}

using Attributes = std::map<std::string, std::string>;

/// Attributes of the start tag that begins at `text[begin]` ('<'), up to its '>'.
/// Enough for the flat files FrameWriter and VTK write; not a general XML parser.
Attributes parse_tag(const std::filesystem::path& file, const std::string& text, std::size_t begin) {
  const std::size_t end = text.find('>', begin);
  if (end == std::string::npos) throw file_error(file, "unterminated tag");
  Attributes attributes;
  std::size_t i = text.find_first_of(" \t\r\n/>", begin);  // skip the element name
  while (i < end) {
    i = text.find_first_not_of(" \t\r\n/", i);
    if (i >= end) break;
    const std::size_t eq = text.find('=', i);
    if (eq == std::string::npos || eq > end) throw file_error(file, "malformed attribute in tag");
    std::string key = text.substr(i, eq - i);
    while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
    const std::size_t quote = text.find_first_not_of(" \t\r\n", eq + 1);
    if (quote >= end || (text[quote] != '"' && text[quote] != '\'')) {
      throw file_error(file, "attribute '" + key + "' is not quoted");
    }
    const std::size_t close = text.find(text[quote], quote + 1);
    if (close == std::string::npos || close > end) throw file_error(file, "unterminated attribute");
    attributes[key] = xml_unescape(text.substr(quote + 1, close - quote - 1));
    i = close + 1;
  }
  return attributes;
}

/// Checks the root element `<VTKFile type="expected_type" ...>`.
void check_root(const std::filesystem::path& file, const std::string& text,
                const std::string& expected_type) {
  const std::size_t root = text.find("<VTKFile");
  if (root == std::string::npos) throw file_error(file, "no <VTKFile> element (not a VTK XML file)");
  const Attributes attributes = parse_tag(file, text, root);
  const auto type = attributes.find("type");
  if (type == attributes.end() || type->second != expected_type) {
    throw file_error(file, "expected VTKFile type=\"" + expected_type + "\"");
  }
  if (text.find("</VTKFile>") == std::string::npos) throw file_error(file, "truncated: no </VTKFile>");
}

/// Attributes of every `<DataSet .../>` element, in file order.
std::vector<Attributes> data_set_tags(const std::filesystem::path& file, const std::string& text) {
  std::vector<Attributes> tags;
  for (std::size_t at = text.find("<DataSet"); at != std::string::npos;
       at = text.find("<DataSet", at + 1)) {
    tags.push_back(parse_tag(file, text, at));
  }
  return tags;
}

const std::string& required(const std::filesystem::path& file, const Attributes& attributes,
                            const std::string& key) {
  const auto it = attributes.find(key);
  if (it == attributes.end()) throw file_error(file, "a <DataSet> has no '" + key + "' attribute");
  return it->second;
}

std::filesystem::path resolve(const std::filesystem::path& from_file, const std::string& relative) {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : from_file.parent_path() / p;
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::filesystem::path& vtu) {
  // VTK only reports a missing file as a generic error; say it plainly.
  if (!std::filesystem::is_regular_file(vtu)) throw file_error(vtu, "missing file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  vtkNew<VtkErrorCatcher> errors;
  // Observers on the reader, its XML parser and its executive, so that a broken file is one
  // exception, not several VTK log lines on stderr.
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetParserErrorObserver(errors);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(vtu.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (errors->failed || grid == nullptr) throw file_error(vtu, "VTK: " + errors->message);
  return grid;
}

}  // namespace

std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd) {
  const std::string text = read_text(pvd);
  check_root(pvd, text, "Collection");
  std::vector<PvdEntry> entries;
  for (const Attributes& tag : data_set_tags(pvd, text)) {
    const std::string& timestep = required(pvd, tag, "timestep");
    double time = 0.0;
    const auto result = std::from_chars(timestep.data(), timestep.data() + timestep.size(), time);
    if (result.ec != std::errc() || result.ptr != timestep.data() + timestep.size()) {
      throw file_error(pvd, "timestep '" + timestep + "' is not a number");
    }
    entries.push_back({time, resolve(pvd, required(pvd, tag, "file"))});
  }
  return entries;
}

std::vector<NamedSurface> read_frame(const std::filesystem::path& vtm) {
  const std::string text = read_text(vtm);
  check_root(vtm, text, "vtkMultiBlockDataSet");
  std::vector<NamedSurface> surfaces;
  for (const Attributes& tag : data_set_tags(vtm, text)) {
    const auto file = tag.find("file");
    if (file == tag.end()) continue;  // an empty block, as VTK writes for null leaves
    const auto name = tag.find("name");
    const auto grid = read_vtu(resolve(vtm, file->second));

    NamedSurface surface;
    surface.name = name == tag.end() ? std::string() : name->second;
    const vtkIdType n = grid->GetNumberOfPoints();
    surface.x.resize(n, 3);
    for (vtkIdType i = 0; i < n; ++i) {
      double p[3];
      grid->GetPoint(i, p);
      surface.x.row(i) << p[0], p[1], p[2];
    }
    const vtkIdType cells = grid->GetNumberOfCells();
    vtkIdType triangles = 0;
    for (vtkIdType c = 0; c < cells; ++c) triangles += grid->GetCellType(c) == VTK_TRIANGLE;
    surface.F.resize(triangles, 3);
    vtkIdType row = 0;
    for (vtkIdType c = 0; c < cells; ++c) {
      if (grid->GetCellType(c) != VTK_TRIANGLE) continue;
      vtkIdType count = 0;
      const vtkIdType* ids = nullptr;
      grid->GetCellPoints(c, count, ids);
      surface.F.row(row++) << static_cast<int>(ids[0]), static_cast<int>(ids[1]),
          static_cast<int>(ids[2]);
    }
    surfaces.push_back(std::move(surface));
  }
  return surfaces;
}

Eigen::MatrixX3d read_point_vectors(const std::filesystem::path& vtu, const std::string& array_name) {
  const auto grid = read_vtu(vtu);
  vtkDataArray* array = grid->GetPointData()->GetArray(array_name.c_str());
  if (array == nullptr) throw file_error(vtu, "no point-data array '" + array_name + "'");
  if (array->GetNumberOfComponents() != 3) {
    throw file_error(vtu, "point-data array '" + array_name + "' does not have 3 components");
  }
  const vtkIdType n = array->GetNumberOfTuples();
  Eigen::MatrixX3d values(n, 3);
  for (vtkIdType i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) values(i, k) = array->GetComponent(i, k);
  }
  return values;
}

}  // namespace stiffsoft
