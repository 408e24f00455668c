#include <stiffsoft/io/background_writer.hpp>

#include <iostream>
#include <stdexcept>

namespace stiffsoft {

BackgroundWriter::BackgroundWriter(std::size_t max_queued) : m_max_queued(max_queued) {
  if (max_queued < 1) throw std::invalid_argument("BackgroundWriter: max_queued must be at least 1");
  m_thread = std::thread([this] { run(); });
}

BackgroundWriter::~BackgroundWriter() {
  {
    const std::lock_guard lock(m_mutex);
    m_closing = true;
  }
  m_added.notify_one();
  m_thread.join();
  if (!m_error || m_error_seen) return;
  try {
    std::rethrow_exception(m_error);
  } catch (const std::exception& e) {
    std::cerr << "stiffsoft: " << e.what() << '\n';
  } catch (...) {
    std::cerr << "stiffsoft: an output job failed\n";
  }
}

void BackgroundWriter::submit(std::function<void()> job) {
  std::unique_lock lock(m_mutex);
  m_done.wait(lock, [&] { return m_error || m_jobs.size() < m_max_queued; });
  rethrow_error();
  m_jobs.push_back(std::move(job));
  lock.unlock();
  m_added.notify_one();
}

void BackgroundWriter::wait() {
  std::unique_lock lock(m_mutex);
  m_done.wait(lock, [&] { return m_error || (m_jobs.empty() && !m_running); });
  rethrow_error();
}

void BackgroundWriter::rethrow_error() {
  if (!m_error) return;
  m_error_seen = true;
  std::rethrow_exception(m_error);
}

void BackgroundWriter::run() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock lock(m_mutex);
      m_added.wait(lock, [&] { return !m_jobs.empty() || m_closing; });
      if (m_jobs.empty()) return;  // closing, and every job has run
      job = std::move(m_jobs.front());
      m_jobs.pop_front();
      m_running = true;
    }
    std::exception_ptr error;
    try {
      job();
    } catch (...) {
      error = std::current_exception();
    }
    {
      const std::lock_guard lock(m_mutex);
      m_running = false;
      if (error) {
        m_error = error;
        m_jobs.clear();  // what follows a failed write would list or flush what is not there
      }
    }
    m_done.notify_all();
  }
}

}  // namespace stiffsoft
