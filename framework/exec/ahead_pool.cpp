#include "exec/ahead_pool.hpp"

#include <algorithm>

namespace brickyard::fw {

AheadPool::AheadPool(int helpers, std::function<void(NodeRuntime&)> run) : run_(std::move(run)) {
  for (int i = 0; i < helpers; ++i) threads_.emplace_back([this] { helper(); });
}

AheadPool::~AheadPool() {
  {
    std::lock_guard<std::mutex> l(m_);
    quit_ = true;
  }
  work_.notify_all();
  for (auto& t : threads_) t.join();
}

void AheadPool::hand_out(NodeRuntime& n) {
  n.ahead.store(1);
  {
    std::lock_guard<std::mutex> l(m_);
    queue_.push_back(&n);
  }
  if (!threads_.empty()) work_.notify_one();
}

void AheadPool::run(NodeRuntime& n) {
  run_(n);
  {
    std::lock_guard<std::mutex> l(m_);
    n.ahead.store(3);
  }
  done_.notify_all();
}

void AheadPool::wait(NodeRuntime& n) {
  std::unique_lock<std::mutex> l(m_);
  while (n.ahead.load() != 3) {
    // Not taken yet: this thread steps it. Taken: this thread steps the next handed-out node
    // meanwhile, or sleeps when there is none.
    auto mine = std::find(queue_.begin(), queue_.end(), &n);
    NodeRuntime* next = mine != queue_.end() ? *mine : queue_.empty() ? nullptr : queue_.front();
    if (!next) {
      done_.wait(l);
      continue;
    }
    queue_.erase(mine != queue_.end() ? mine : queue_.begin());
    next->ahead.store(2);
    l.unlock();
    run(*next);
    l.lock();
  }
}

void AheadPool::helper() {
  std::unique_lock<std::mutex> l(m_);
  for (;;) {
    work_.wait(l, [this] { return quit_ || !queue_.empty(); });
    if (quit_) return;
    NodeRuntime* n = queue_.front();
    queue_.pop_front();
    n->ahead.store(2);
    l.unlock();
    run(*n);
    l.lock();
  }
}

}  // namespace brickyard::fw
