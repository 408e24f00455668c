// Every query of the CCD benchmark (../shared/data/ccd-queries, Wang et al. 2021) with zero false
// negatives; false positives are counted and printed per folder. Every reported time of impact
// must leave the primitives apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <stiffsoft/coupling/ccd/query_file.hpp>

namespace stiffsoft::ccd {
namespace {

namespace fs = std::filesystem;

/// Counts of one folder (scene/kind).
struct Counts {
  int queries = 0;
  int collisions = 0;
  int false_negatives = 0;
  int false_positives = 0;
};

std::vector<fs::path> query_files(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file() && entry.path().extension() == ".csv") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(CcdDataset, NoFalseNegativesAndCollisionFreeTimes) {
  const fs::path root = fs::path(STIFFSOFT_SHARED_DIR) / "data" / "ccd-queries";
  if (!fs::is_directory(root)) {
    GTEST_SKIP() << "CCD query folder missing: " << root.string();
  }
  const CcdSettings settings;
  std::map<std::string, Counts> folders;
  Counts total;
  int checked_times = 0;
  const std::vector<fs::path> files = query_files(root);
  ASSERT_FALSE(files.empty()) << "no *.csv under " << root.string();
  for (const fs::path& file : files) {
    const CcdQueryKind kind = ccd_query_kind(file);
    const std::string folder = fs::relative(file.parent_path(), root).generic_string();
    Counts& c = folders[folder];
    const std::vector<CcdQuery> queries = read_ccd_queries(file);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const CcdQuery& q = queries[i];
      const double toi = query_toi(kind, q, settings);
      ASSERT_GE(toi, 0.0);
      ASSERT_LE(toi, settings.t_max);
      const bool reported = toi < settings.t_max;
      ++c.queries;
      c.collisions += q.collides;
      if (q.collides && !reported) {
        ++c.false_negatives;
        ADD_FAILURE() << "false negative: " << file.string() << " query " << i;
      }
      c.false_positives += !q.collides && reported;
      if (reported && query_distance(kind, q, 0) > 0) {
        // Collision-free toi: positive distance at toi and (sampled) on [0, toi].
        ++checked_times;
        for (int k = 0; k <= 64; ++k) {
          const long double t = static_cast<long double>(toi) * k / 64;
          ASSERT_GT(query_distance(kind, q, t), 0.0L)
              << file.string() << " query " << i << " toi=" << toi << " t=" << static_cast<double>(t);
        }
      }
    }
  }
  std::printf("%-40s %8s %6s %6s %6s\n", "folder", "queries", "hits", "FN", "FP");
  for (const auto& [folder, c] : folders) {
    std::printf("%-40s %8d %6d %6d %6d\n", folder.c_str(), c.queries, c.collisions,
                c.false_negatives, c.false_positives);
    total.queries += c.queries;
    total.collisions += c.collisions;
    total.false_negatives += c.false_negatives;
    total.false_positives += c.false_positives;
  }
  std::printf("%-40s %8d %6d %6d %6d\n", "TOTAL", total.queries, total.collisions,
              total.false_negatives, total.false_positives);
  std::printf("collision-free toi checked on %d reported queries\n", checked_times);
  EXPECT_EQ(total.queries, 5324);  // the README's count: a parse error would change it
  EXPECT_EQ(total.collisions, 426);
  EXPECT_EQ(total.false_negatives, 0);
}

TEST(CcdDataset, UnreadableFileThrows) {
  EXPECT_THROW(read_ccd_queries("/nonexistent/vertex-face/data.csv"), std::runtime_error);
  EXPECT_THROW(ccd_query_kind("/somewhere/else.csv"), std::runtime_error);
}

}  // namespace
}  // namespace stiffsoft::ccd
