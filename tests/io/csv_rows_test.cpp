/// @file Reading a run's CSV files back for a resume: csv_end_through_step, which reads a long
/// file from its end, keeps exactly the whole rows through a step.
#include <stiffsoft/io/csv_rows.hpp>

#include <gtest/gtest.h>

#include <fstream>

#include <stiffsoft/io/checkpoint.hpp>

#include "../temporary_folder.hpp"

namespace stiffsoft {
namespace {

const std::vector<std::string> kColumns{"step", "body", "x"};

/// A file with the header of kColumns, then `per_step` rows for each step 0 … last, each
/// `width` characters long, then `tail` (a partial line, say).
std::filesystem::path write_rows(const std::filesystem::path& file, int last, int per_step, int width,
                                 const std::string& tail = "") {
  std::ofstream out(file, std::ios::binary);
  out << "step,body,x\n";
  for (int step = 0; step <= last; ++step)
    for (int body = 0; body < per_step; ++body) {
      std::string row = std::to_string(step) + ",b" + std::to_string(body) + ",";
      row.resize(std::size_t(std::max<int>(width, int(row.size()))), '7');
      out << row << '\n';
    }
  out << tail;
  return file;
}

const std::string kHeader = "step,body,x\n";

TEST(CsvRows, TheEndFoundFromTheFilesEndKeepsEveryWholeRowThroughTheStep) {
  const auto dir = testing::temporary_folder("csv_rows");
  // Rows of 400 bytes, 600 a step: 240 kB a step, so the 1 MB blocks end inside rows and steps.
  const int last = 30, per_step = 600, width = 400;
  for (const std::string& tail : {std::string(), std::string("31,b0,12")}) {
    const auto file = write_rows(dir / "bodies.csv", last, per_step, width, tail);
    for (int step : {-1, 0, 1, 7, 20, 29, 30, 31, 1000}) {
      const int kept = std::min(step, last);  // the partial line is never kept
      const std::uintmax_t length = kHeader.size() + std::uintmax_t(kept + 1) * per_step * (width + 1);
      const CsvEnd end = csv_end_through_step(file, kColumns, step);
      EXPECT_EQ(end.length, length) << "through step " << step << ", tail '" << tail << "'";
      EXPECT_EQ(end.last_step, kept) << "through step " << step;
    }
  }
}

TEST(CsvRows, AFileWithoutWholeRowsKeepsItsHeader) {
  const auto dir = testing::temporary_folder("csv_rows");
  for (const std::string& tail : {std::string(), std::string("0,b0"), std::string("0,b0,1")}) {
    const auto file = write_rows(dir / "bodies.csv", -1, 0, 0, tail);
    const CsvEnd end = csv_end_through_step(file, kColumns, 5);
    EXPECT_EQ(end.length, kHeader.size()) << tail;
    EXPECT_EQ(end.last_step, -1) << tail;
  }
}

TEST(CsvRows, AnotherHeaderNoFileOrALineWithoutAStepIsAResumeErrorNamingTheFile) {
  const auto dir = testing::temporary_folder("csv_rows");
  const auto file = write_rows(dir / "bodies.csv", 3, 2, 10);
  try {
    csv_end_through_step(file, {"step", "body", "y"}, 3);
    FAIL() << "no error for another header";
  } catch (const ResumeError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies.csv: not the header this version writes"), std::string::npos) << e.what();
  }
  EXPECT_THROW(csv_end_through_step(dir / "missing.csv", kColumns, 3), ResumeError);
  // A quoted name with a line break: the record's second line starts with no step, and the cut
  // would fall inside the record.
  std::ofstream(dir / "broken.csv", std::ios::binary) << kHeader << "0,b0,1\n0,\"two\nlines\",1\n";
  try {
    csv_end_through_step(dir / "broken.csv", kColumns, 0);
    FAIL() << "no error for a line without a step";
  } catch (const ResumeError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.csv: a line that does not start with a step number"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace stiffsoft
