#pragma once
// The sim clock's helpers: threads that step nodes handed out ahead of their turn (see
// sim_scheduler.cpp). The scheduler's own thread works too: waiting for a node, it steps that
// node itself when no helper has taken it yet, or another one handed out, so with no helpers at
// all (one thread) every handed-out step still runs, at its turn.
#include "exec/node_runtime.hpp"

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace brickyard::fw {

class AheadPool {
 public:
  // run: steps a node ahead of its turn (its effects deferred); called on any of the threads.
  AheadPool(int helpers, std::function<void(NodeRuntime&)> run);
  ~AheadPool();
  AheadPool(const AheadPool&) = delete;
  AheadPool& operator=(const AheadPool&) = delete;

  void hand_out(NodeRuntime& n);  // n.ahead must be 0; it becomes 1
  // Returns once n (handed out) has stepped.
  void wait(NodeRuntime& n);

 private:
  void run(NodeRuntime& n);  // claimed (ahead 2): step it, then mark it stepped (3)
  void helper();
  std::function<void(NodeRuntime&)> run_;
  std::mutex m_;
  std::condition_variable work_, done_;
  std::deque<NodeRuntime*> queue_;  // handed out, not yet claimed
  bool quit_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace brickyard::fw
