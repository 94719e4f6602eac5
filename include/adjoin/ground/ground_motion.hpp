#pragma once
// The ground-motion source interface.
//
// A source gives the model's forcing a_g(t) = -u''(t) in the solver's dimensionless units
// (accelerations in g, time in units of T0). Sources built from records negate the recorded
// acceleration u'' accordingly; the sign matters only for phase relations, never for spectra.
//
// The solver samples a source on its own uniform grid; a source must be cheap to evaluate,
// deterministic and safe to call from several threads at once (const).
#include <limits>
#include <memory>
#include <string>

namespace adjoin {

class GroundMotion {
 public:
  virtual ~GroundMotion() = default;
  // a_g at dimensionless time t >= 0.
  virtual double ag(double t) const = 0;
  // A one-line description for summaries ("decaying-sine u0=1.5 omega=1.5 k=0.5").
  virtual std::string describe() const = 0;
  // The time after which the source is identically zero (infinity if it never is).
  virtual double duration() const { return std::numeric_limits<double>::infinity(); }
  // The sampling interval of a sampled source (a record), dimensionless; 0 for a function.
  virtual double sample_interval() const { return 0.0; }
};

}  // namespace adjoin
