#include <stiffsoft/io/background_writer.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace stiffsoft {
namespace {

TEST(BackgroundWriter, RunsTheJobsInTheOrderGivenOnAThreadOfItsOwn) {
  std::vector<int> order;
  std::thread::id worker;
  {
    BackgroundWriter writer;
    for (int k = 0; k < 100; ++k)
      writer.submit([&, k] {
        order.push_back(k);
        worker = std::this_thread::get_id();
      });
    writer.wait();
    ASSERT_EQ(order.size(), 100u);
    EXPECT_NE(worker, std::this_thread::get_id());
  }
  for (int k = 0; k < 100; ++k) EXPECT_EQ(order[k], k);
}

TEST(BackgroundWriter, WaitReturnsOnlyOnceTheRunningJobHasFinished) {
  BackgroundWriter writer;
  std::atomic<bool> finished = false;
  writer.submit([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    finished = true;
  });
  writer.wait();
  EXPECT_TRUE(finished);
}

TEST(BackgroundWriter, TheDestructorRunsTheJobsStillQueued) {
  std::atomic<int> ran = 0;
  {
    BackgroundWriter writer;
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    writer.submit([released] { released.wait(); });
    for (int k = 0; k < 5; ++k) writer.submit([&] { ++ran; });
    EXPECT_EQ(ran, 0);  // all behind the first job, which waits
    release.set_value();
  }
  EXPECT_EQ(ran, 5);
}

TEST(BackgroundWriter, SubmitBlocksWhileTheBoundOfJobsWait) {
  BackgroundWriter writer(2);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> started;
  writer.submit([&started, released] {
    started.set_value();
    released.wait();
  });
  started.get_future().wait();  // running, no longer queued
  writer.submit([] {});
  writer.submit([] {});  // two queued: the bound
  std::atomic<bool> third_queued = false;
  std::thread caller([&] {
    writer.submit([] {});
    third_queued = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(third_queued);
  release.set_value();
  caller.join();
  EXPECT_TRUE(third_queued);
  writer.wait();
}

TEST(BackgroundWriter, AFailedJobStopsTheQueueAndItsErrorComesBackToTheCaller) {
  BackgroundWriter writer;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> ran = 0;
  writer.submit([released] {
    released.wait();
    throw std::runtime_error("cannot write out/frames/a.vtu");
  });
  writer.submit([&] { ++ran; });  // queued behind the failing job: dropped
  release.set_value();
  try {
    writer.wait();
    FAIL() << "wait() did not rethrow the job's error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write out/frames/a.vtu");
  }
  EXPECT_THROW(writer.submit([&] { ++ran; }), std::runtime_error);  // and every later call
  EXPECT_THROW(writer.wait(), std::runtime_error);
  EXPECT_EQ(ran, 0);
}

TEST(BackgroundWriter, AnErrorNoCallerSawIsReportedOnStandardError) {
  ::testing::internal::CaptureStderr();
  {
    BackgroundWriter writer;
    writer.submit([] { throw std::runtime_error("cannot append to out/stats.csv"); });
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "stiffsoft: cannot append to out/stats.csv\n");
}

TEST(BackgroundWriter, RefusesABoundOfZero) { EXPECT_THROW(BackgroundWriter(0), std::invalid_argument); }

}  // namespace
}  // namespace stiffsoft
