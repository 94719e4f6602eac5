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
#include <utility>

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

// Another source times a constant, e.g. 1/g: a dimensionless ground (in the model's units) as
// the structure solver reads it (in g). `inner` must outlive it.
class ScaledGround final : public GroundMotion {
 public:
  ScaledGround(const GroundMotion& inner, double factor) : inner_(inner), factor_(factor) {}
  double ag(double t) const override { return inner_.ag(t) * factor_; }
  std::string describe() const override { return inner_.describe(); }
  double duration() const override { return inner_.duration(); }
  double sample_interval() const override { return inner_.sample_interval(); }

 private:
  const GroundMotion& inner_;
  double factor_;
};

// A source times a plain factor, owning it: the scene's `ground.scale` (a suite's scale factor,
// an IDA's intensity level) on any source, applied after everything the source does (its
// processing, its ground.scale_pga). A factor of 2 doubles every a_g exactly.
class ScaledMotion final : public GroundMotion {
 public:
  ScaledMotion(std::shared_ptr<const GroundMotion> inner, double factor) : inner_(std::move(inner)), factor_(factor) {}
  double ag(double t) const override { return inner_->ag(t) * factor_; }
  std::string describe() const override;
  double duration() const override { return inner_->duration(); }
  double sample_interval() const override { return inner_->sample_interval(); }
  const GroundMotion& inner() const { return *inner_; }
  double factor() const { return factor_; }

 private:
  std::shared_ptr<const GroundMotion> inner_;
  double factor_;
};

// The source times `factor` (ground.scale): `ground` itself for 1, a ScaledMotion otherwise.
// FieldError("ground.scale") unless factor is a finite number > 0.
std::shared_ptr<const GroundMotion> scale_ground(std::shared_ptr<const GroundMotion> ground, double factor);

// The source under any ScaledMotion wrappers (what a source was built as, e.g. a RecordMotion).
const GroundMotion& unscaled_ground(const GroundMotion& ground);

}  // namespace adjoin
