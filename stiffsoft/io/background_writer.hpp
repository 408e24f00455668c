#pragma once
/// @file One thread of its own that runs a run's output jobs (frames, CSV rows, checkpoints) in
/// order, so that the simulation's next steps overlap the writing of the last ones.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace stiffsoft {

/// Runs the jobs given to submit() one after another, in the order given, on a thread of its
/// own. A job must own (or capture by value) everything it reads that the caller goes on
/// changing. At most `max_queued` jobs wait: submit() blocks while that many do, so a writer
/// that falls behind holds back the caller instead of filling memory. The first job that throws
/// stops the queue: the jobs queued after it are dropped, and its exception is rethrown by every
/// later submit() and wait(), so the caller learns of it at its next call.
class BackgroundWriter {
 public:
  /// Jobs that may wait at once unless told otherwise: on the 562-body pile `full` at
  /// h = 1/240, about three frames (four steps' rows and a frame each) ahead of the writing.
  static constexpr std::size_t kMaxQueued = 16;

  /// Starts the thread; `max_queued` ≥ 1 (std::invalid_argument otherwise).
  explicit BackgroundWriter(std::size_t max_queued = kMaxQueued);
  /// Runs the jobs still queued, then ends the thread. A job's error that no submit() or wait()
  /// rethrew is reported on stderr (a destructor must not throw).
  ~BackgroundWriter();
  BackgroundWriter(const BackgroundWriter&) = delete;             ///< one thread, one owner
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;  ///< one thread, one owner

  /// Queues `job` after the jobs submitted before it; blocks while `max_queued` jobs wait.
  /// Rethrows an earlier job's error instead of queuing.
  void submit(std::function<void()> job);
  /// Returns once every job submitted has run; rethrows the first job's error.
  void wait();

 private:
  /// The thread's loop: takes the oldest job, runs it, until the destructor closes the queue.
  void run();
  /// With the lock held: rethrows the stored error, if any, and remembers it was seen.
  void rethrow_error();

  std::mutex m_mutex;                          ///< guards everything below but m_thread
  std::condition_variable m_added;             ///< a job was queued, or the queue closed
  std::condition_variable m_done;              ///< a job finished
  std::deque<std::function<void()>> m_jobs;    ///< jobs not yet started, oldest first
  std::size_t m_max_queued;                    ///< bound on m_jobs' size
  bool m_running = false;                      ///< a job is running now
  bool m_closing = false;                      ///< the destructor waits for the last jobs
  std::exception_ptr m_error;                  ///< the first job's error, or null
  bool m_error_seen = false;                   ///< m_error was rethrown to the caller
  std::thread m_thread;                        ///< last: started once the rest exists
};

}  // namespace stiffsoft
