// The processes (MPI ranks) that render one frame together, as render_frame sees them: a
// work counter they share (the paper's "next work item" variable at cluster scale) and the
// few collective exchanges a wave needs. The MPI implementation is renderer/parallel/mpi_ranks.*;
// render_frame calls these a few times per wave, never per ray. The MPI group also watches
// for a rank that stops answering (see MpiSession::ranks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tessera {

enum class RankScheduler : std::uint8_t { dynamic, stat };  // stat: one block of tiles per rank

class RankGroup {
 public:
  virtual ~RankGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Every rank calls it before a wave of `count` work items: the counter restarts at 0.
  virtual void start_wave(std::size_t count) = 0;
  // The next items [first, second) for this rank, at most `batch` of them; empty when the
  // wave's items are all handed out.
  virtual std::pair<std::size_t, std::size_t> next_items(std::size_t batch) = 0;
  // Every rank's bytes, in rank order, on every rank.
  virtual std::vector<std::vector<char>> all_gather(const std::vector<char>& mine) = 0;
  // Every rank's bytes, in rank order, on rank 0 (nothing on the others).
  virtual std::vector<std::vector<char>> gather(const std::vector<char>& mine) = 0;
  virtual bool any(bool flag) = 0;  // true on every rank when it is true on one
  virtual std::uint64_t sum(std::uint64_t value) = 0;
  virtual void barrier() = 0;  // returns when every rank has called it
  // Tells the others this rank is working, between the calls above: a rank rendering whole
  // frames alone calls it between sample waves.
  virtual void alive() = 0;
  // Lets MPI serve the other ranks' requests to this rank's memory (the counter and notes
  // live at rank 0): over a network without remote atomics in hardware (TCP), a request
  // waits until the target rank enters MPI. Rank 0 calls it between its tiles.
  virtual void progress() = 0;
  // Seconds this rank has spent inside the calls above (waiting for the others, moving data,
  // taking work from the counter): its communication time.
  virtual double communication_seconds() const = 0;
};

}  // namespace tessera
