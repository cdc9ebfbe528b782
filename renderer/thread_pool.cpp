#include "rayview/thread_pool.h"

#include <algorithm>
#include <utility>

namespace rayview {

ThreadPool::ThreadPool(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  workers_.reserve(static_cast<std::size_t>(threads));
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { workerLoop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::parallelFor(std::size_t count, const std::function<void(std::size_t)>& task) {
  if (count == 0) return;
  std::lock_guard submit(submitMutex_);
  std::unique_lock lock(mutex_);
  task_ = &task;
  count_ = count;
  next_.store(0, std::memory_order_relaxed);
  finishedWorkers_ = 0;
  ++jobGeneration_;
  wake_.notify_all();
  done_.wait(lock, [&] { return finishedWorkers_ == workers_.size(); });
  task_ = nullptr;
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

void ThreadPool::workerLoop() {
  std::uint64_t seenGeneration = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || jobGeneration_ != seenGeneration; });
    if (stopping_) return;
    seenGeneration = jobGeneration_;
    const auto* task = task_;
    const std::size_t count = count_;
    lock.unlock();
    std::exception_ptr failure;
    try {
      for (std::size_t index = next_.fetch_add(1); index < count; index = next_.fetch_add(1)) (*task)(index);
    } catch (...) {
      failure = std::current_exception();
      next_.store(count);  // no further index is handed out
    }
    lock.lock();
    if (failure && !failure_) failure_ = failure;
    if (++finishedWorkers_ == workers_.size()) done_.notify_one();
  }
}

}  // namespace rayview
