#include "studies/executor.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace rodlab::validation::study {

std::vector<Json> run_tasks(const std::vector<std::function<Json()>>& tasks,
                            const Executor& executor) {
  const int rank = executor.processes ? executor.processes->rank() : 0;
  const int ranks = executor.processes ? executor.processes->size() : 1;
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(rank); i < tasks.size();
       i += static_cast<std::size_t>(ranks))
    mine.push_back(i);

  std::vector<Json> results(mine.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress;
  long finished = 0;
  auto worker = [&] {
    for (std::size_t k = next++; k < mine.size(); k = next++) {
      try {
        results[k] = tasks[mine[k]]();
      } catch (const std::exception& e) {
        results[k] = Json{{"error", e.what()}};
      } catch (...) {
        results[k] = Json{{"error", "unknown exception"}};
      }
      if (executor.progress) {
        const std::lock_guard lock(progress);
        executor.progress(++finished, static_cast<long>(mine.size()));
      }
    }
  };
  const int threads = std::max(1, std::min<int>(executor.jobs, static_cast<int>(mine.size())));
  if (threads == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }

  if (ranks == 1) return results;
  Json share = Json::array();
  for (std::size_t k = 0; k < mine.size(); ++k) share.push_back({mine[k], results[k]});
  const auto texts = executor.processes->gather(share.dump());
  if (!executor.processes->root()) return {};
  std::vector<Json> all(tasks.size());
  for (const auto& text : texts)
    for (const auto& item : Json::parse(text)) all[item[0].get<std::size_t>()] = item[1];
  return all;
}

}  // namespace rodlab::validation::study
