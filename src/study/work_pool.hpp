#pragma once
// Independent tasks on a few threads: each worker takes the next task from a shared counter, so a
// long task never holds up the others. Tasks share nothing but what they read; each writes only
// its own result slot, so results do not depend on the number of threads or their timing.

#include <cstddef>
#include <functional>
#include <vector>

namespace tumble::study {

/// Runs task(i) for every i of `order` (started in that order: longest first balances best) on
/// `jobs` threads while the calling thread waits, calling progress(done) on it as tasks finish.
/// After a task throws no new task starts; once all threads have stopped, the exception of the
/// lowest-numbered failed task is rethrown.
void run_tasks(const std::vector<std::size_t>& order, int jobs,
               const std::function<void(std::size_t)>& task,
               const std::function<void(int done)>& progress);

}  // namespace tumble::study
