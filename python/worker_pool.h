// A fixed set of threads that run one batch of numbered tasks at a time (cablelab.rollout): the
// threads live as long as the pool, so a batch per simulation step costs a wake-up, not a thread
// start.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace cablelab::python {

class WorkerPool {
 public:
  /// `threads` threads in all, the caller of forEach being one of them (threads = 1: no helper).
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Runs task(0) ... task(count - 1), each once, spread over the threads; returns when all are
  /// done. task must not throw (catch inside it).
  void forEach(int count, const std::function<void(int)>& task);

 private:
  void helperLoop();
  void drain();

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  const std::function<void(int)>* task_ = nullptr;
  int count_ = 0, next_ = 0, helpersWorking_ = 0;
  long batch_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> helpers_;
};

}  // namespace cablelab::python
