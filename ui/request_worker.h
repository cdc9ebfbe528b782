#pragma once
// "Latest request wins" on one persistent worker thread: the shape of the viewer's background tasks (loading
// a scene, measuring the speed-for-accuracy trade). The UI thread submits requests and never waits; the worker
// runs one at a time. A new request (or cancel()) supersedes the one running: its cancel flag is raised, and
// only the newest request's result is ever handed back. No GL here.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace rayview {

template <typename Request, typename Result>
class RequestWorker {
 public:
  // Runs on the worker for each request it takes. `cancel` is raised when the request is superseded (or the
  // worker stops): check it where stopping early is worth it, and return whatever Result says "cancelled".
  using Work = std::function<Result(std::uint64_t id, const Request& request, const std::atomic<bool>& cancel)>;

  // Starts the worker thread: `work` may use its owner's members, so declare the RequestWorker after them
  // (it is then destroyed, and its thread joined, first).
  explicit RequestWorker(Work work) : work_(std::move(work)), thread_([this] { loop(); }) {}

  ~RequestWorker() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
      cancel_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  RequestWorker(const RequestWorker&) = delete;
  RequestWorker& operator=(const RequestWorker&) = delete;

  // Called on the worker after each request (e.g. to wake the UI loop). Set it before submitting.
  void setFinishedListener(std::function<void()> listener) {
    std::lock_guard lock(mutex_);
    listener_ = std::move(listener);
  }

  // Returns at once with the request's id; the running request, if any, is cancelled.
  std::uint64_t submit(Request request) {
    std::uint64_t id;
    {
      std::lock_guard lock(mutex_);
      id = ++latestId_;
      pending_ = std::move(request);
      result_.reset();  // an older result not yet taken is stale now
      cancel_ = true;   // the running one, if any; lowered when the worker takes this request
    }
    wake_.notify_all();
    return id;
  }

  // Drops the pending request and any result, and cancels the running one, whose result (saying it was
  // cancelled, if it noticed) is still handed back. Returns at once.
  void cancel() {
    std::lock_guard lock(mutex_);
    pending_.reset();
    result_.reset();
    cancel_ = true;
  }

  // The result of the newest request, once, when it is ready.
  std::optional<Result> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(result_, std::nullopt);
  }

  bool busy() const {
    std::lock_guard lock(mutex_);
    return running_.has_value() || pending_.has_value();
  }

  // The request waiting, else the one running (for progress displays).
  std::optional<Request> current() const {
    std::lock_guard lock(mutex_);
    return pending_ ? pending_ : running_;
  }

 private:
  void loop() {
    for (;;) {
      std::uint64_t id;
      Request request;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || pending_.has_value(); });
        if (stopping_) return;
        request = std::move(*pending_);
        pending_.reset();
        running_ = request;
        id = latestId_;
        cancel_ = false;  // under the lock: a submit() or cancel() from now on reaches this run
      }
      Result result = work_(id, request, cancel_);
      request = Request{};  // let go of what the request holds before reporting
      std::function<void()> listener;
      {
        std::lock_guard lock(mutex_);
        running_.reset();
        // Only the newest request's result is handed back; a superseded one is dropped here (and freed).
        if (id == latestId_ && !pending_) result_ = std::move(result);
        listener = listener_;
      }
      if (listener) listener();
    }
  }

  Work work_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Request> pending_;   // guarded by mutex_
  std::optional<Request> running_;   // guarded by mutex_
  std::uint64_t latestId_ = 0;       // guarded by mutex_
  std::optional<Result> result_;     // guarded by mutex_
  std::function<void()> listener_;   // guarded by mutex_
  bool stopping_ = false;            // guarded by mutex_
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace rayview
