/// @file Reading a run's CSV files back for a resume: csv_end_through_step, which reads a long
/// file from its end, keeps exactly the bytes csv_rows_through_step reads from its start.
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

/// What csv_rows_through_step keeps, as csv_end_through_step reports it.
CsvEnd read_from_start(const std::filesystem::path& file, int last_step) {
  const CsvRows rows = csv_rows_through_step(file, kColumns, last_step);
  return {std::string("step,body,x\n").size() + rows.text.size(), rows.last_step};
}

TEST(CsvRows, TheEndFoundFromTheFilesEndIsTheOneReadFromItsStart) {
  const auto dir = testing::temporary_folder("csv_rows");
  // Rows of 400 bytes, 600 a step: 240 kB a step, so the 1 MB blocks end inside rows and steps.
  for (const std::string& tail : {std::string(), std::string("31,b0,12")}) {
    const auto file = write_rows(dir / "bodies.csv", 30, 600, 400, tail);
    for (int step : {-1, 0, 1, 7, 20, 29, 30, 31, 1000}) {
      const CsvEnd from_end = csv_end_through_step(file, kColumns, step);
      const CsvEnd from_start = read_from_start(file, step);
      EXPECT_EQ(from_end.length, from_start.length) << "through step " << step << ", tail '" << tail << "'";
      EXPECT_EQ(from_end.last_step, from_start.last_step) << "through step " << step;
    }
    EXPECT_EQ(csv_end_through_step(file, kColumns, 30).length,
              std::filesystem::file_size(file) - tail.size());  // the partial line is dropped
  }
}

TEST(CsvRows, AFileWithoutWholeRowsKeepsItsHeader) {
  const auto dir = testing::temporary_folder("csv_rows");
  for (const std::string& tail : {std::string(), std::string("0,b0"), std::string("0,b0,1")}) {
    const auto file = write_rows(dir / "bodies.csv", -1, 0, 0, tail);
    const CsvEnd end = csv_end_through_step(file, kColumns, 5);
    EXPECT_EQ(end.length, std::string("step,body,x\n").size()) << tail;
    EXPECT_EQ(end.last_step, -1) << tail;
  }
}

TEST(CsvRows, AnotherHeaderOrNoFileIsAResumeErrorNamingTheFile) {
  const auto dir = testing::temporary_folder("csv_rows");
  const auto file = write_rows(dir / "bodies.csv", 3, 2, 10);
  try {
    csv_end_through_step(file, {"step", "body", "y"}, 3);
    FAIL() << "no error for another header";
  } catch (const ResumeError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies.csv: not the header this version writes"), std::string::npos) << e.what();
  }
  EXPECT_THROW(csv_end_through_step(dir / "missing.csv", kColumns, 3), ResumeError);
  EXPECT_THROW(csv_rows_through_step(dir / "missing.csv", kColumns, 3), ResumeError);
}

}  // namespace
}  // namespace stiffsoft
