#include "work_pool.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace tumble::study {

void run_tasks(const std::vector<std::size_t>& order, int jobs,
               const std::function<void(std::size_t)>& task,
               const std::function<void(int done)>& progress) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards done, error, error_index
  std::condition_variable changed;
  int done = 0;
  std::exception_ptr error;
  std::size_t error_index = 0;

  auto worker = [&] {
    for (;;) {
      const std::size_t k = next.fetch_add(1);
      if (k >= order.size() || failed.load()) return;
      const std::size_t i = order[k];
      std::exception_ptr e;
      try {
        task(i);
      } catch (...) {
        e = std::current_exception();
        failed.store(true);
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ++done;
        if (e && (!error || i < error_index)) error = e, error_index = i;
      }
      changed.notify_one();
    }
  };
  const std::size_t threads = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)),
                                                      1, std::max<std::size_t>(order.size(), 1));
  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    int reported = -1;
    for (;;) {
      if (done != reported) {
        reported = done;
        lock.unlock();
        if (progress) progress(reported);
        lock.lock();
      }
      // After a failure the workers stop by themselves; join() below waits for the running ones.
      if (done == static_cast<int>(order.size()) || failed.load()) break;
      changed.wait_for(lock, std::chrono::milliseconds(100));
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace tumble::study
