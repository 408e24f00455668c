#include <stiffsoft/study/runner.hpp>

#include <apps/cli/petsc_arguments.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstring>
#include <deque>
#include <fstream>
#include <stdexcept>

#include <stiffsoft/io/atomic_file.hpp>

extern char** environ;

namespace stiffsoft::study {

namespace {

using Clock = std::chrono::steady_clock;

/// The environment without MPI launcher variables.
std::vector<std::string> child_environment() {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    if (!is_mpi_launcher_variable(*e)) env.emplace_back(*e);
  }
  return env;
}

/// Starts `args` with stdout and stderr going to `log`; returns the pid.
pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& log, const std::vector<std::string>& env) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv, envp;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0].c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(rc));
  return pid;
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/// A run in flight.
struct Job {
  const RunPlan* plan = nullptr;
  RunResult result;
  Clock::time_point start;
  bool checking = false;
};

bool load_cached(const std::filesystem::path& file, const std::string& hash, RunResult& result) {
  std::ifstream in(file);
  if (!in) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("hash").get<std::string>() != hash) return false;
    result.exit_code = j.at("exit_code").get<int>();
    result.check_code = j.at("check_code").get<int>();
    result.wall_seconds = j.at("wall_seconds").get<double>();
    result.cached = true;
    return true;
  } catch (const std::exception&) {
    return false;  // unreadable: run again
  }
}

}  // namespace

std::map<std::string, RunResult> run_all(const std::vector<const RunPlan*>& runs, const RunnerOptions& options) {
  std::map<std::string, RunResult> results;
  std::deque<const RunPlan*> todo;
  for (const RunPlan* plan : runs) {
    if (results.contains(plan->hash)) continue;
    RunResult r;
    r.dir = options.runs / plan->hash;
    if (load_cached(r.dir / "result.json", plan->hash, r)) {
      results[plan->hash] = r;
      continue;
    }
    results[plan->hash] = r;
    todo.push_back(plan);
  }
  const std::size_t total = todo.size();
  if (total > 0)
    spdlog::info("study: {} runs to do ({} cached), {} at a time", total, results.size() - total, options.jobs);
  const std::vector<std::string> env = child_environment();
  const std::string binary = options.binary.string();
  std::map<pid_t, Job> running;
  std::size_t done = 0;
  auto start_run = [&](const RunPlan* plan) {
    Job job;
    job.plan = plan;
    job.result = results[plan->hash];
    std::filesystem::create_directories(job.result.dir);
    write_file_atomically(job.result.dir / "scene.json", [&](std::ostream& os) { os << plan->scene.dump(2) << '\n'; });
    job.start = Clock::now();
    const pid_t pid = spawn({binary, "run", (job.result.dir / "scene.json").string(), "-o", job.result.dir.string(),
                             "--threads", std::to_string(options.threads)},
                            job.result.dir / "run.log", env);
    running[pid] = job;
  };
  while (!todo.empty() || !running.empty()) {
    while (!todo.empty() && int(running.size()) < options.jobs) {
      start_run(todo.front());
      todo.pop_front();
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) throw std::runtime_error(std::string("study: waiting for runs failed: ") + std::strerror(errno));
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not ours
    Job job = it->second;
    running.erase(it);
    if (!job.checking) {
      job.result.wall_seconds = std::chrono::duration<double>(Clock::now() - job.start).count();
      job.result.exit_code = exit_code_of(status);
      const std::filesystem::path pvd = job.result.dir / "scene.pvd";  // frames are named after scene.json
      if (options.check && (job.result.exit_code == 0 || job.result.exit_code == 3) && std::filesystem::exists(pvd)) {
        job.checking = true;
        running[spawn({binary, "check", pvd.string()}, job.result.dir / "check.log", env)] = job;
        continue;
      }
    } else {
      job.result.check_code = exit_code_of(status);
    }
    const nlohmann::json record{{"hash", job.plan->hash},
                                {"exit_code", job.result.exit_code},
                                {"check_code", job.result.check_code},
                                {"wall_seconds", job.result.wall_seconds}};
    write_file_atomically(job.result.dir / "result.json", [&](std::ostream& os) { os << record.dump(2) << '\n'; });
    results[job.plan->hash] = job.result;
    ++done;
    spdlog::info("study: run {}/{} {} ({}{}) done in {:.1f} s, exit {}{}", done, total, job.plan->hash,
                 job.plan->series.empty() ? "" : job.plan->series + ", ", job.plan->x, job.result.wall_seconds,
                 job.result.exit_code, job.result.check_code == 1 ? ", frames intersect" : "");
  }
  return results;
}

int run_process(const std::vector<std::string>& args, const std::filesystem::path& log) {
  pid_t pid = 0;
  try {
    pid = spawn(args, log, child_environment());
  } catch (const std::exception&) {
    return 127;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  return exit_code_of(status);
}

}  // namespace stiffsoft::study
