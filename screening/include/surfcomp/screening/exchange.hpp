// What a screen needs of the processes it runs on (screen_queries): which one this is, how many
// there are, and two collective calls. One process is SingleProcess; the program's MPI path
// (tools/screen_mpi.cpp) is another, so that the screen itself is written once.
#pragma once

#include <cstdint>
#include <vector>

namespace surfcomp::screening {

/// The processes of a screen. Every process makes the same collective calls in the same order.
class Exchange {
 public:
  virtual ~Exchange() = default;
  /// This process, 0 to processes() - 1; process 0 ranks the hits and gets them.
  virtual int process() const = 0;
  virtual int processes() const = 0;
  /// Every process's `local` numbers, on process 0 in process order; empty on the others.
  virtual std::vector<double> gather(const std::vector<double>& local) = 0;
  /// Process 0's `values`, on every process.
  virtual std::vector<std::uint64_t> broadcast(std::vector<std::uint64_t> values) = 0;
};

/// One process alone: gather and broadcast give back what they are given.
class SingleProcess final : public Exchange {
 public:
  int process() const override { return 0; }
  int processes() const override { return 1; }
  std::vector<double> gather(const std::vector<double>& local) override { return local; }
  std::vector<std::uint64_t> broadcast(std::vector<std::uint64_t> values) override {
    return values;
  }
};

}  // namespace surfcomp::screening
