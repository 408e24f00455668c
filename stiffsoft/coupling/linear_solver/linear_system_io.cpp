#include <stiffsoft/coupling/linear_solver/linear_system_io.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace stiffsoft {

namespace {

std::string format(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

void write_file(const std::filesystem::path& path, const std::string& content) {
  std::ofstream out(path);
  out << content;
  if (!out) throw std::runtime_error("save_linear_system: cannot write " + path.string());
}

/// The lines of a MatrixMarket file after its header line, comments dropped.
std::vector<std::string> data_lines(const std::filesystem::path& path, const std::string& expected_header) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("load_linear_system: cannot open " + path.string());
  std::string header;
  std::getline(in, header);
  if (header != expected_header)
    throw std::runtime_error("load_linear_system: " + path.string() + ":1: header '" + header +
                             "'; expected '" + expected_header + "'");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '%') lines.push_back(line);
  return lines;
}

}  // namespace

void save_linear_system(const LinearSystem& s, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const Eigen::SparseMatrix<double> lower = s.upper.transpose();
  std::string m =
      "%%MatrixMarket matrix coordinate real symmetric\n% stiffsoft Newton system " + s.name + "\n";
  m += std::to_string(lower.rows()) + " " + std::to_string(lower.cols()) + " " +
       std::to_string(lower.nonZeros()) + "\n";
  for (int j = 0; j < lower.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, j); it; ++it)
      m +=
          std::to_string(it.row() + 1) + " " + std::to_string(it.col() + 1) + " " + format(it.value()) + "\n";
  write_file(dir / (s.name + ".mtx"), m);
  std::string v = "%%MatrixMarket matrix array real general\n" + std::to_string(s.b.size()) + " 1\n";
  for (const double x : s.b) v += format(x) + "\n";
  write_file(dir / (s.name + "_b.mtx"), v);
}

LinearSystem load_linear_system(const std::filesystem::path& dir, const std::string& name) {
  LinearSystem s;
  s.name = name;
  const std::filesystem::path matrix_path = dir / (name + ".mtx"), vector_path = dir / (name + "_b.mtx");
  const std::vector<std::string> m =
      data_lines(matrix_path, "%%MatrixMarket matrix coordinate real symmetric");
  long rows = 0, cols = 0, nnz = 0;
  if (m.empty() || !(std::istringstream(m[0]) >> rows >> cols >> nnz) || rows != cols || rows <= 0 ||
      long(m.size()) != nnz + 1)
    throw std::runtime_error("load_linear_system: " + matrix_path.string() +
                             ": bad size line or entry count");
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(nnz);
  for (long k = 1; k <= nnz; ++k) {
    long i = 0, j = 0;
    double v = 0;
    if (!(std::istringstream(m[k]) >> i >> j >> v) || i < 1 || j < 1 || i > rows || j > cols || i < j)
      throw std::runtime_error("load_linear_system: " + matrix_path.string() + ": bad entry '" + m[k] +
                               "' (expected 'row column value' in the lower triangle)");
    triplets.emplace_back(int(j - 1), int(i - 1), v);  // transposed: the upper triangle
  }
  s.upper.resize(rows, cols);
  s.upper.setFromTriplets(triplets.begin(), triplets.end());
  s.upper.makeCompressed();
  const std::vector<std::string> v = data_lines(vector_path, "%%MatrixMarket matrix array real general");
  long n = 0, one = 0;
  if (v.empty() || !(std::istringstream(v[0]) >> n >> one) || n != rows || one != 1 ||
      long(v.size()) != n + 1)
    throw std::runtime_error("load_linear_system: " + vector_path.string() + ": expected " +
                             std::to_string(rows) + " values");
  s.b.resize(n);
  for (long i = 0; i < n; ++i) s.b[i] = std::stod(v[i + 1]);
  return s;
}

}  // namespace stiffsoft
