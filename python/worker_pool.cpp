#include "python/worker_pool.h"

namespace cablelab::python {

WorkerPool::WorkerPool(int threads) {
  for (int i = 1; i < threads; ++i) helpers_.emplace_back([this] { helperLoop(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

void WorkerPool::forEach(int count, const std::function<void(int)>& task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task, count_ = count, next_ = 0;
    helpersWorking_ = static_cast<int>(helpers_.size());
    ++batch_;
  }
  wake_.notify_all();
  drain();
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [this] { return helpersWorking_ == 0; });
  task_ = nullptr;
}

void WorkerPool::drain() {
  for (;;) {
    int i;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (next_ >= count_) return;
      i = next_++;
    }
    (*task_)(i);
  }
}

void WorkerPool::helperLoop() {
  long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || batch_ != seen; });
      if (stopping_) return;
      seen = batch_;
    }
    drain();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --helpersWorking_;
    }
    finished_.notify_one();
  }
}

}  // namespace cablelab::python
