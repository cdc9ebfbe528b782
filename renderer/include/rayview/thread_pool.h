#pragma once
// A persistent pool of worker threads. Threads are created once, never per frame or per pass.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rayview {

class ThreadPool {
 public:
  // `threads` <= 0: one per hardware thread.
  explicit ThreadPool(int threads = 0);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()); }

  // Runs task(index) for every index in [0, count) on the workers and returns when all have finished.
  // Indices are handed out in increasing order. Concurrent calls are served one after another.
  // The calling thread only waits: the viewer's UI thread never calls this. A task that throws (std::bad_alloc)
  // stops the handing out of further indices, and the first exception is rethrown here once all have finished.
  void parallelFor(std::size_t count, const std::function<void(std::size_t index)>& task);

 private:
  void workerLoop();

  std::vector<std::thread> workers_;
  std::mutex submitMutex_;  // one job at a time

  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;
  std::atomic<std::size_t> next_{0};
  std::size_t finishedWorkers_ = 0;
  std::exception_ptr failure_;  // the job's first exception, under mutex_
  std::uint64_t jobGeneration_ = 0;
  bool stopping_ = false;
};

}  // namespace rayview
