#include <stiffsoft/coupling/ccd/query_file.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include <stiffsoft/coupling/ccd/distance.hpp>
#include <stiffsoft/coupling/ccd/edge_edge_ccd.hpp>
#include <stiffsoft/coupling/ccd/point_triangle_ccd.hpp>

namespace stiffsoft::ccd {
namespace {

/// Parses the integer in `token` as a correctly rounded double; throws on junk.
double parse_integer(const std::string& token, const std::filesystem::path& file, int line) {
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size()) {
    throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": not an integer: '" +
                             token + "'");
  }
  return value;
}

}  // namespace

std::vector<CcdQuery> read_ccd_queries(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) {
    throw std::runtime_error("cannot open CCD query file " + file.string());
  }
  std::vector<CcdQuery> queries;
  std::string row;
  int line = 0;
  CcdQuery query;
  int vertex = 0;
  while (std::getline(in, row)) {
    ++line;
    if (!row.empty() && row.back() == '\r') row.pop_back();
    if (row.empty()) continue;
    std::array<std::string, 7> tokens;
    std::size_t begin = 0;
    int count = 0;
    for (; count < 7 && begin <= row.size(); ++count) {
      const std::size_t comma = row.find(',', begin);
      tokens[count] = row.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
      begin = comma == std::string::npos ? row.size() + 1 : comma + 1;
    }
    if (count != 7 || begin <= row.size()) {
      throw std::runtime_error(file.string() + ":" + std::to_string(line) +
                               ": expected 7 comma-separated integers");
    }
    for (int k = 0; k < 3; ++k) {
      const double num = parse_integer(tokens[2 * k], file, line);
      const double den = parse_integer(tokens[2 * k + 1], file, line);
      if (den == 0) {
        throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": zero denominator");
      }
      query.vertices[vertex][k] = num / den;
    }
    const bool truth = parse_integer(tokens[6], file, line) != 0;
    if (vertex == 0) {
      query.collides = truth;
    } else if (truth != query.collides) {
      throw std::runtime_error(file.string() + ":" + std::to_string(line) +
                               ": ground truth differs within one query");
    }
    if (++vertex == 8) {
      queries.push_back(query);
      vertex = 0;
    }
  }
  if (vertex != 0) {
    throw std::runtime_error(file.string() + ": row count is not a multiple of 8");
  }
  return queries;
}

CcdQueryKind ccd_query_kind(const std::filesystem::path& file) {
  const std::string path = file.generic_string();
  if (path.find("vertex-face") != std::string::npos) return CcdQueryKind::point_triangle;
  if (path.find("edge-edge") != std::string::npos) return CcdQueryKind::edge_edge;
  throw std::runtime_error("cannot tell the query kind of " + path +
                           ": its path names neither 'vertex-face' nor 'edge-edge'");
}

long double query_distance(CcdQueryKind kind, const CcdQuery& query, long double t) {
  using Vec = detail::Vec3<long double>;
  std::array<Vec, 4> x;
  for (int i = 0; i < 4; ++i) {
    x[i] = (1 - t) * query.vertices[i].cast<long double>() +
           t * query.vertices[i + 4].cast<long double>();
  }
  const long double d2 =
      kind == CcdQueryKind::point_triangle
          ? detail::point_triangle_distance_squared<long double>(x[0], x[1], x[2], x[3])
          : detail::segment_segment_distance_squared<long double>(x[0], x[1], x[2], x[3]);
  return std::sqrt(d2);
}

double query_toi(CcdQueryKind kind, const CcdQuery& query, const CcdSettings& settings) {
  const auto& v = query.vertices;
  return kind == CcdQueryKind::point_triangle
             ? point_triangle_toi(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], settings)
             : edge_edge_toi(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], settings);
}

}  // namespace stiffsoft::ccd
