#pragma once
// A run's channels as arrays: the times, the channel names and a matrix of their values (one
// row per kept grid point, one column per channel), for a program that wants the histories
// rather than files.
//
//     ChannelRecorder recorder({"A.x5", "B.x3", "link1.force"});
//     run(spec, &recorder);
//     recorder.times();            // [s], rows of values()
//     recorder.values().col(2);    // link1.force [N]
//
// Channels are named as structure/channels.hpp names them (A.x3, A.a3_abs, A.drift2,
// A.shear2, A.base_shear, link1.force, link1.stroke, contact1.gap, contact1.force); no names:
// every channel of the structure. Memory is taken once, when the run begins (t_end / h / every
// rows), and a step stores without allocating. A run that restarts (begin() again: a
// tolerance's ladder) keeps the last run's values.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/observe/channel_values.hpp"
#include "adjoin/solver/structure_solver.hpp"

namespace adjoin {

class ChannelRecorder final : public StructureObserver {
 public:
  // `every`: keep every n-th grid point (1: all; the first is t = 0).
  explicit ChannelRecorder(std::vector<std::string> names = {}, std::size_t every = 1);
  ChannelRecorder(const ChannelRecorder&) = delete;  // its channel reader points into it
  ChannelRecorder& operator=(const ChannelRecorder&) = delete;

  // FieldError ("channels[2]") when a name is not a channel of the structure.
  void begin(const structure::Structure& s, const StructureSolverOptions& options) override;
  void observe(const StructureState& state) override;

  const std::vector<std::string>& names() const { return names_; }
  // The kept grid points' times [s] and values (rows: times, columns: names), SI units.
  Eigen::Map<const Eigen::VectorXd> times() const { return {times_.data(), static_cast<Eigen::Index>(rows_)}; }
  Eigen::Block<const Eigen::MatrixXd> values() const { return values_.topRows(static_cast<Eigen::Index>(rows_)); }
  // One channel's history, by name (FieldError if it was not recorded).
  Eigen::VectorXd column(const std::string& name) const;

 private:
  std::vector<std::string> asked_, names_;
  std::size_t every_ = 1, seen_ = 0, rows_ = 0;
  structure::Structure structure_;  // the values read it
  ChannelValues reader_;
  Eigen::VectorXd times_;
  Eigen::MatrixXd values_;
  Eigen::VectorXd row_;
};

}  // namespace adjoin
