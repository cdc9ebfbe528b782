#pragma once
// Sends that complete in the background, for every rank's loop: each message's bytes stay alive until its send has
// completed, and nothing waits on a rank that may be gone.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "mpi_link.h"

namespace rayview::cluster {

// Completes `request`, giving up after `patience` (its receiver gone): never a hang.
inline bool completeWithin(MPI_Request& request, std::chrono::milliseconds patience) {
  const auto deadline = std::chrono::steady_clock::now() + patience;
  for (;;) {
    int done = 0;
    if (request == MPI_REQUEST_NULL) return true;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(kProbePause);
  }
}

class Outbox {
 public:
  using Bytes = std::vector<std::uint8_t>;
  // Whether a rank is lost: a send to it may never complete, so it is neither tested nor waited for, and its bytes
  // are never freed (MPI may still read them).
  using Lost = std::function<bool(int rank)>;

  explicit Outbox(Lost lost = [](int) { return false; }) : lost_(std::move(lost)) {}
  ~Outbox() { release(); }
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  void send(int rank, int tag, Bytes bytes) {
    auto shared = std::make_shared<const Bytes>(std::move(bytes));
    sendPart(rank, tag, shared, 0, shared->size());
  }
  // `size` bytes of `bytes` from `offset` (a large message in pieces shares one buffer).
  void sendPart(int rank, int tag, const std::shared_ptr<const Bytes>& bytes, std::size_t offset, std::size_t size) {
    pending_.push_back({bytes, rank, MPI_REQUEST_NULL});
    MPI_Isend(bytes->data() + offset, static_cast<int>(size), MPI_BYTE, rank, tag, MPI_COMM_WORLD,
              &pending_.back().request);
    reap();
  }

  // Lets go of the sends that completed.
  void reap() {
    std::erase_if(pending_, [this](Pending& out) {
      int done = 0;
      if (!lost_(out.rank)) MPI_Test(&out.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }
  // Waits up to `patience` for every send to a rank not lost. False when some did not complete.
  bool drain(std::chrono::milliseconds patience) {
    const auto deadline = std::chrono::steady_clock::now() + patience;
    for (;;) {
      reap();
      const bool waiting = std::any_of(pending_.begin(), pending_.end(), [this](const Pending& out) {
        return !lost_(out.rank);
      });
      if (!waiting) return true;
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(kProbePause);
    }
  }

 private:
  struct Pending {
    std::shared_ptr<const Bytes> bytes;
    int rank = 0;
    MPI_Request request = MPI_REQUEST_NULL;
  };
  // Sends still pending when the outbox goes (to a lost rank) keep their bytes until the process ends: MPI may
  // still read them.
  void release() {
    for (Pending& out : pending_) keepForMpi(out.bytes);
  }

  Lost lost_;
  std::deque<Pending> pending_;
};

}  // namespace rayview::cluster
