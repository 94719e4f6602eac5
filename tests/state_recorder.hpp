#pragma once
// Every state of a structure run, kept in memory: the tests' trajectory recorder.
#include <vector>

#include "adjoin/structure/observer.hpp"

namespace adjoin::test {

class StateRecorder final : public StructureObserver {
 public:
  void observe(const StructureState& s) override { states.push_back(s); }
  std::vector<StructureState> states;
};

}  // namespace adjoin::test
