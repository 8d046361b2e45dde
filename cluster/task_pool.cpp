// The task pool: a shared queue on rank 0, worker threads on every rank, text messages between.
#include "cluster/task_pool.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

#include <nlohmann/json.hpp>

#include "solver/core/clock.hpp"

namespace asperity::cluster {
namespace {
using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// Message tags. A worker thread w of a rank asks on kAsk and is answered on kAnswer + w (each
// thread its own tag, so answers cannot cross); a rank whose workers are all done says so on
// kRankDone; rank 0 sends every report on kReports.
constexpr int kAsk = 11, kRankDone = 12, kReports = 13, kAnswer = 1000;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Json to_json(const TaskReport& r) {
  return {{"task", r.task},         {"rank", r.rank},           {"failed", r.failed},
          {"skipped", r.skipped},   {"postponed", r.postponed}, {"cpu", r.cpu_seconds},
          {"busy", r.busy_seconds}, {"note", r.note},           {"payload", r.payload}};
}

TaskReport from_json(const Json& j) {
  return {.task = j.at("task").get<int>(),
          .rank = j.at("rank").get<int>(),
          .failed = j.at("failed").get<bool>(),
          .skipped = j.at("skipped").get<bool>(),
          .postponed = j.at("postponed").get<bool>(),
          .cpu_seconds = j.at("cpu").get<double>(),
          .busy_seconds = j.at("busy").get<double>(),
          .note = j.at("note").get<std::string>(),
          .payload = j.at("payload").get<std::string>()};
}

TaskReport timed_run(const std::function<TaskReport(int)>& run, int task, int rank) {
  const auto t0 = Clock::now();
  const double cpu0 = thread_and_children_cpu_seconds();
  TaskReport r = run(task);
  r.task = task;
  r.rank = rank;
  r.cpu_seconds = thread_and_children_cpu_seconds() - cpu0;
  r.busy_seconds = since(t0);
  return r;
}

// Rank 0's side: the queue, the reports, the progress callback.
class Queue {
 public:
  Queue(int tasks, const std::vector<int>& order,
        const std::function<void(const TaskReport&, int)>& on_report)
      : order_(order), on_report_(on_report), reports_(static_cast<std::size_t>(tasks)) {}

  // The next task, or -1 when none is left.
  int take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (next_ < order_.size()) {
      ++running_;
      return order_[next_++];
    }
    if (!drained_) drained_ = since(start_);
    return -1;
  }
  void record(TaskReport r) {
    std::lock_guard<std::mutex> lock(mutex_);
    --running_;
    busy_ += r.busy_seconds;
    last_ = since(start_);
    if (on_report_) on_report_(r, running_);
    reports_[static_cast<std::size_t>(r.task)] = std::move(r);
  }
  std::vector<TaskReport>& reports() { return reports_; }
  PoolStats stats(int workers) const {
    PoolStats s;
    s.workers = workers;
    s.wall_seconds = last_;
    s.busy_seconds = busy_;
    s.idle_fraction =
        workers > 0 && last_ > 0 ? 1 - busy_ / (static_cast<double>(workers) * last_) : 0;
    s.drain_seconds = drained_ ? std::max(0.0, last_ - *drained_) : 0;
    return s;
  }

 private:
  std::mutex mutex_;
  const std::vector<int>& order_;
  const std::function<void(const TaskReport&, int)>& on_report_;
  std::vector<TaskReport> reports_;
  std::size_t next_ = 0;
  int running_ = 0;
  double busy_ = 0, last_ = 0;
  std::optional<double> drained_;
  Clock::time_point start_ = Clock::now();
};

// A worker thread on a rank other than 0: ask, run, report with the next ask.
void remote_worker(World& world, int w, const std::function<TaskReport(int)>& run) {
  Json report = nullptr;
  for (;;) {
    world.send(0, kAsk, Json{{"worker", w}, {"report", report}}.dump());
    const int task = std::stoi(world.receive(0, kAnswer + w));
    if (task < 0) return;
    report = to_json(timed_run(run, task, world.rank()));
  }
}

// Starts up to `count` threads running `body(w)` (w = first, first + 1, ...) into `pool`, and
// returns how many started. A thread that cannot start (the process's thread or address-space
// limit: each reserves its stack) ends the starting, not the run: the threads already started,
// and the caller's own, do the work.
template <class Body>
int start_threads(std::vector<std::thread>& pool, int first, int count, const Body& body) {
  int started = 0;
  for (int w = first; w < first + count; ++w) {
    try {
      pool.emplace_back(body, w);
    } catch (const std::system_error&) {
      break;
    }
    ++started;
  }
  return started;
}

}  // namespace

int worker_count(int threads, int tasks) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return std::clamp(threads, 1, std::max(1, std::min(tasks, cores)));
}

std::vector<TaskReport> run_tasks(World& world, int tasks, const std::vector<int>& order,
                                  int threads, const std::function<TaskReport(int)>& run,
                                  const std::function<void(const TaskReport&, int)>& on_report,
                                  PoolStats* stats) {
  threads = worker_count(threads, tasks);
  if (!world.root()) {
    std::vector<std::thread> pool;
    // Worker 0 is this thread; rank 0 counts the workers each rank reports.
    const int started =
        start_threads(pool, 1, threads - 1, [&](int w) { remote_worker(world, w, run); });
    remote_worker(world, 0, run);
    for (std::thread& t : pool) t.join();
    world.send(0, kRankDone, std::to_string(started + 1));
    std::vector<TaskReport> reports(static_cast<std::size_t>(tasks));
    for (const Json& j : Json::parse(world.receive(0, kReports))) {
      TaskReport r = from_json(j);
      reports[static_cast<std::size_t>(r.task)] = std::move(r);
    }
    return reports;
  }

  Queue queue(tasks, order, on_report);
  auto local_worker = [&] {
    for (int task = queue.take(); task >= 0; task = queue.take()) {
      queue.record(timed_run(run, task, 0));
    }
  };
  std::vector<std::thread> pool;
  int workers = 1 + start_threads(pool, 1, threads - 1, [&](int) { local_worker(); });
  if (world.size() == 1) {
    local_worker();
  } else {
    // The coordinator takes this thread: one more worker thread (if none can start, the other
    // ranks' workers do the tasks).
    workers = workers - 1 + start_threads(pool, 0, 1, [&](int) { local_worker(); });
    // The coordinator: answer asks until every other rank has reported its workers done.
    for (int ranks_done = 0; ranks_done < world.size() - 1;) {
      bool idle = true;
      if (auto [from, text] = world.try_receive_any(kAsk); from >= 0) {
        idle = false;
        const Json ask = Json::parse(text);
        if (!ask.at("report").is_null()) queue.record(from_json(ask.at("report")));
        world.send(from, kAnswer + ask.at("worker").get<int>(), std::to_string(queue.take()));
      }
      if (auto [from, text] = world.try_receive_any(kRankDone); from >= 0) {
        idle = false;
        ++ranks_done;
        workers += std::stoi(text);
      }
      if (idle) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  for (std::thread& t : pool) t.join();
  if (world.size() > 1) {
    Json all = Json::array();
    for (const TaskReport& r : queue.reports()) {
      if (r.task >= 0) all.push_back(to_json(r));
    }
    const std::string text = all.dump();
    for (int r = 1; r < world.size(); ++r) world.send(r, kReports, text);
  }
  if (stats != nullptr) *stats = queue.stats(workers);
  return std::move(queue.reports());
}

}  // namespace asperity::cluster
