#include "renderer/parallel/schedulers.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "renderer/util/named_enum.h"

namespace tessera {

const std::vector<std::string>& scheduler_names() {
  static const std::vector<std::string> names = {"tiles", "chunks", "counter", "interleaved"};
  return names;
}

const char* scheduler_name(SchedulerKind kind) { return enum_name(scheduler_names(), kind); }

SchedulerKind parse_scheduler(const std::string& name) {
  return parse_enum<SchedulerKind>(scheduler_names(), name, "scheduler");
}

std::vector<int> chunk_rows(int height, int threads) {
  std::vector<int> rows(threads + 1);
  const int per = height / threads;
  for (int t = 0; t < threads; ++t) rows[t] = t * per;
  rows[threads] = height;
  return rows;
}

namespace {

// Cuts every tile at the block boundaries; items keep the tile order within each block.
void split_into_chunks(WorkPlan& plan, const std::vector<WorkItem>& ordered) {
  const int n = plan.params.threads;
  const std::vector<int> rows = chunk_rows(plan.params.height, n);
  plan.chunk_begin.assign(1, 0);
  for (int c = 0; c < n; ++c) {
    for (const WorkItem& item : ordered) {
      const int y0 = std::max(item.rect.y0, rows[c]), y1 = std::min(item.rect.y1, rows[c + 1]);
      if (y0 < y1) plan.items.push_back({{item.rect.x0, y0, item.rect.x1, y1}, item.tile, c});
    }
    plan.chunk_begin.push_back(plan.items.size());
  }
}

// Runs thread_main(t) for t in [0, n) on n threads: n - 1 new ones and the caller.
template <typename F>
void on_n_threads(int n, const F& thread_main) {
  std::vector<std::thread> pool;
  pool.reserve(n - 1);
  for (int t = 1; t < n; ++t) pool.emplace_back([&, t] { thread_main(t); });
  thread_main(0);
  for (std::thread& th : pool) th.join();
}

void run_chunks(const WorkPlan& plan, const ItemBody& body) {
  on_n_threads(plan.params.threads, [&](int t) {
    for (std::size_t i = plan.chunk_begin[t]; i < plan.chunk_begin[t + 1]; ++i) body(i, t);
  });
}

void run_interleaved(const WorkPlan& plan, const ItemBody& body) {
  const std::size_t n = plan.params.threads;
  on_n_threads(plan.params.threads, [&](int t) {
    for (std::size_t i = t; i < plan.items.size(); i += n) body(i, t);
  });
}

void run_counter(const WorkPlan& plan, const ItemBody& body) {
  // One counter for everyone; its cache line ping-pongs once per tile, not per ray.
  alignas(64) std::atomic<std::size_t> next{0};
  on_n_threads(plan.params.threads, [&](int t) {
    for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < plan.items.size();) body(i, t);
  });
}

}  // namespace

WorkPlan make_work_plan(const WorkPlanParams& params) {
  WorkPlan plan;
  plan.params = params;
  plan.grid = tile_grid(params.width, params.height, params.tile_size);
  plan.tiles = make_tiles(params.width, params.height, params.tile_size);
  std::vector<WorkItem> ordered;
  ordered.reserve(plan.tiles.size());
  for (int t : tile_order(plan.grid, params.order)) ordered.push_back({plan.tiles[t], t, 0});
  if (params.scheduler == SchedulerKind::chunks) split_into_chunks(plan, ordered);
  else plan.items = std::move(ordered);
  return plan;
}

// TBB only lets an arena have as many threads as the process allows (the core count by
// default), so more threads than cores need a global_control for the frame. TBB also starts
// its workers lazily: one still starting when the first wave begins misses most of it, so
// all the threads meet once before the frame.
struct WaveRunner::Arena {
  explicit Arena(int threads)
      : control(tbb::global_control::max_allowed_parallelism,
                static_cast<std::size_t>(std::max(threads, tbb::info::default_concurrency()))),
        arena(threads) {
    gather(threads);
  }

  void gather(int threads) {
    // Each of n tasks waits until n have started, so n distinct threads must run them. The
    // deadline only matters if TBB cannot give the arena n threads.
    std::atomic<int> arrived{0};
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    arena.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<int>(0, threads, 1),
          [&](const tbb::blocked_range<int>&) {
            ++arrived;
            while (arrived.load() < threads && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
          },
          tbb::simple_partitioner());
    });
  }

  tbb::global_control control;
  tbb::task_arena arena;
};

WaveRunner::WaveRunner(const WorkPlan& plan) : plan_(plan) {
  if (plan.params.scheduler == SchedulerKind::tiles) arena_ = std::make_unique<Arena>(plan.params.threads);
}

void WaveRunner::run_batches(const NextBatch& next, const ItemBody& body) {
  if (!arena_) arena_ = std::make_unique<Arena>(plan_.params.threads);
  const std::size_t threads = static_cast<std::size_t>(plan_.params.threads);
  const std::thread::id caller = std::this_thread::get_id();
  arena_->arena.execute([&] {
    tbb::task_group group;
    std::atomic<std::size_t> waiting{0};  // items handed to the group, not yet started
    bool more = true;  // touched by the calling thread only
    std::function<void()> refill = [&] {
      while (more && waiting.load() < threads) {
        const auto [begin, end] = next();
        if (begin >= end) {
          more = false;
          break;
        }
        waiting += end - begin;
        for (std::size_t i = begin; i < end; ++i)
          group.run([&, i] {
            --waiting;
            body(i, tbb::this_task_arena::current_thread_index());
            if (std::this_thread::get_id() == caller) refill();
          });
      }
    };
    refill();
    group.wait();
  });
}

WaveRunner::~WaveRunner() = default;

void WaveRunner::run(const ItemBody& body) {
  switch (plan_.params.scheduler) {
    case SchedulerKind::tiles:
      arena_->arena.execute([&] {
        run_tiles_dynamic(plan_.items.size(), [&](std::size_t i) {
          body(i, tbb::this_task_arena::current_thread_index());
        });
      });
      break;
    case SchedulerKind::chunks: run_chunks(plan_, body); break;
    case SchedulerKind::counter: run_counter(plan_, body); break;
    case SchedulerKind::interleaved: run_interleaved(plan_, body); break;
  }
}

}  // namespace tessera
