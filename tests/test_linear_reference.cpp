// LinearReference (exact response of the linear cases: damper stuck throughout, or no damper)
// against
//  - the closed-form response of an undamped oscillator when both rods are elastic;
//  - an independent numerical inversion of the same Laplace transforms along a Bromwich line
//    (GSL QAWF), for fractional and mixed rods;
//  - the equations of motion themselves, by finite differences of its own output, and the
//    fractional Zener laws by Grünwald–Letnikov derivatives of its own output;
//  - the paper's weak scene, which must stay stuck, and its values from mpmath at 50 digits.
#include <catch2/catch.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/study/linear_reference.hpp"

namespace {

using adjoin::LinearReference;
using adjoin::LinearResponse;
using adjoin::Model;
using adjoin::Rod;
using cplx = std::complex<double>;

struct Ground {
  double u0, omega, k;
  double ag(double t) const { return u0 * omega * omega * std::exp(-k * t) * std::sin(omega * t); }
};

const Ground kWeak{0.05, 3.5, 0.3};

// x'' + w^2 x = u0 W^2 e^{-kt} sin(Wt), x(0) = x'(0) = 0: particular solution Im(a e^{st}),
// s = -k + iW, a = u0 W^2 / (s^2 + w^2), plus the free vibration that cancels its initial
// displacement Im(a) and velocity Im(a s).
struct Oscillator {
  double w;
  Ground g;
  double x(double t) const {
    const cplx s(-g.k, g.omega);
    const cplx a = g.u0 * g.omega * g.omega / (s * s + w * w);
    return std::imag(a * std::exp(s * t)) - std::imag(a) * std::cos(w * t) -
           std::imag(a * s) / w * std::sin(w * t);
  }
  double v(double t) const {
    const cplx s(-g.k, g.omega);
    const cplx a = g.u0 * g.omega * g.omega / (s * s + w * w);
    return std::imag(a * s * std::exp(s * t)) + std::imag(a) * w * std::sin(w * t) -
           std::imag(a * s) * std::cos(w * t);
  }
};

Model elastic_model(double rho, double eps) {
  Model m;
  m.rho = rho;
  m.eps = eps;
  m.mu = 0.0;
  m.rod1 = Rod::Elastic();
  m.rod2 = Rod::Elastic();
  return m;
}

// ---- independent Bromwich inversion (GSL QAWF) of the transforms of the brief ----
struct Transform {
  Model m;
  Ground g;
  bool stuck;
  int block;   // 1 or 2 (case b)
  int output;  // 0 x, 1 v, 2 f (of the block's own rod; case a: 2 f1, 3 f2)
  double sigma = 0.0;

  static cplx rod(const Rod& r, double stiffness, cplx s) {
    if (r.elastic) return stiffness;
    const cplx z = std::pow(s, r.order);
    return stiffness * (1.0 + r.tau_x * z) / (1.0 + r.tau_f * z);
  }
  cplx operator()(cplx s) const {
    const cplx a = g.u0 * g.omega * g.omega * g.omega / ((s + g.k) * (s + g.k) + g.omega * g.omega);
    const cplx g1 = rod(m.rod1, 1.0, s), g2 = rod(m.rod2, m.eps, s);
    cplx x, f;
    if (stuck) {
      const double c = m.rho / (m.rho + 1.0);
      x = a / (s * s + c * (g1 + g2));
      f = (output == 3 ? g2 : g1) * x;
    } else if (block == 1) {
      x = a / (s * s + g1);
      f = g1 * x;
    } else {
      x = a / (s * s + m.rho * g2);
      f = g2 * x;
    }
    return output == 0 ? x : output == 1 ? s * x : f;
  }
};

double bromwich(Transform z, double t) {
  z.sigma = std::min(1.0, 1.0 / t);
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(2000);
  gsl_integration_workspace* cw = gsl_integration_workspace_alloc(2000);
  gsl_integration_qawo_table* cos_table = gsl_integration_qawo_table_alloc(t, 1.0, GSL_INTEG_COSINE, 30);
  gsl_integration_qawo_table* sin_table = gsl_integration_qawo_table_alloc(t, 1.0, GSL_INTEG_SINE, 30);
  auto re = [](double omega, void* p) {
    const Transform& zz = *static_cast<Transform*>(p);
    return zz(cplx(zz.sigma, omega)).real();
  };
  auto im = [](double omega, void* p) {
    const Transform& zz = *static_cast<Transform*>(p);
    return zz(cplx(zz.sigma, omega)).imag();
  };
  gsl_function fre{re, &z}, fim{im, &z};
  double rc = 0, ec = 0, rs = 0, es = 0;
  const int sc = gsl_integration_qawf(&fre, 0.0, 1e-14, 2000, w, cw, cos_table, &rc, &ec);
  const int ss = gsl_integration_qawf(&fim, 0.0, 1e-14, 2000, w, cw, sin_table, &rs, &es);
  gsl_integration_qawo_table_free(cos_table);
  gsl_integration_qawo_table_free(sin_table);
  gsl_integration_workspace_free(cw);
  gsl_integration_workspace_free(w);
  gsl_set_error_handler(old);
  CHECK(sc == GSL_SUCCESS);
  CHECK(ss == GSL_SUCCESS);
  return std::exp(z.sigma * t) / std::numbers::pi * (rc - rs);
}

// Five-point central differences.
template <class F>
double d1(const F& f, double t, double h) {
  return (f(t - 2 * h) - 8 * f(t - h) + 8 * f(t + h) - f(t + 2 * h)) / (12 * h);
}
template <class F>
double d2(const F& f, double t, double h) {
  return (-f(t - 2 * h) + 16 * f(t - h) - 30 * f(t) + 16 * f(t + h) - f(t + 2 * h)) / (12 * h * h);
}

}  // namespace

TEST_CASE("elastic rods, no damper: the closed-form oscillator response", "[linear_reference]") {
  const Model m = elastic_model(0.7, 3.0);
  const LinearReference ref(m, kWeak.u0, kWeak.omega, kWeak.k, false);
  const Oscillator block1{1.0, kWeak}, block2{std::sqrt(0.7 * 3.0), kWeak};
  CHECK(std::abs(ref.natural_pole(1) - cplx(0.0, 1.0)) < 1e-14);
  CHECK(std::abs(ref.natural_pole(2) - cplx(0.0, std::sqrt(2.1))) < 1e-14);
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.04 * i;
    const LinearResponse r = ref.at(t);
    worst = std::max({worst, std::abs(r.x[0] - block1.x(t)), std::abs(r.v[0] - block1.v(t)),
                      std::abs(r.x[1] - block2.x(t)), std::abs(r.v[1] - block2.v(t)),
                      std::abs(r.storey_force[0] - block1.x(t)), std::abs(r.storey_force[1] - 3.0 * block2.x(t))});
    REQUIRE(r.link_force == 0.0);
  }
  CHECK(worst < 1e-11);
}

TEST_CASE("elastic rods, damper stuck: the closed-form oscillator with w^2 = c(1 + eps)",
          "[linear_reference]") {
  const Model m = elastic_model(0.5, 2.0);
  const Ground g{1.5, 1.5, 0.5};
  const LinearReference ref(m, g.u0, g.omega, g.k, true);
  const double c = 0.5 / 1.5;
  const Oscillator x{std::sqrt(c * 3.0), g};
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.04 * i;
    const LinearResponse r = ref.at(t);
    REQUIRE(r.x[0] == r.x[1]);
    REQUIRE(r.v[0] == r.v[1]);
    worst = std::max({worst, std::abs(r.x[0] - x.x(t)), std::abs(r.v[0] - x.v(t)),
                      std::abs(r.storey_force[0] - x.x(t)), std::abs(r.storey_force[1] - 2.0 * x.x(t)),
                      std::abs(r.link_force - (0.5 * 2.0 * x.x(t) - x.x(t)) / 1.5)});
  }
  CHECK(worst < 1e-11);
}

TEST_CASE("fractional rods: agreement with a direct Bromwich-line inversion (QAWF)",
          "[linear_reference]") {
  Model paper = Model::Paper();
  Model mixed = Model::Paper();
  mixed.rod1 = Rod::Elastic();
  mixed.rod2 = Rod{0.8, 2.0, 0.5, false};
  mixed.rho = 1.3;
  mixed.eps = 0.7;
  struct Case {
    Model m;
    Ground g;
    bool stuck;
  };
  for (const Case& cs : {Case{paper, kWeak, true}, Case{paper, Ground{1.5, 1.5, 0.5}, false},
                         Case{mixed, Ground{0.3, 2.0, 0.1}, true},
                         Case{mixed, Ground{0.3, 2.0, 0.1}, false}}) {
    const LinearReference ref(cs.m, cs.g.u0, cs.g.omega, cs.g.k, cs.stuck);
    for (double t : {0.05, 0.7, 2.3, 5.0, 11.0, 16.0}) {
      const LinearResponse r = ref.at(t);
      Transform z{cs.m, cs.g, cs.stuck, 1, 0};
      const double scale = cs.g.u0 * cs.g.omega * cs.g.omega;
      INFO("stuck " << cs.stuck << ", t = " << t);
      z.output = 0;
      CHECK(std::abs(r.x[0] - bromwich(z, t)) < 1e-11 * scale);
      z.output = 1;
      CHECK(std::abs(r.v[0] - bromwich(z, t)) < 1e-11 * scale);
      z.output = 2;
      CHECK(std::abs(r.storey_force[0] - bromwich(z, t)) < 1e-11 * scale);
      if (cs.stuck) {
        z.output = 3;
        CHECK(std::abs(r.storey_force[1] - bromwich(z, t)) < 1e-11 * scale);
      } else {
        z.block = 2;
        z.output = 0;
        CHECK(std::abs(r.x[1] - bromwich(z, t)) < 1e-11 * scale);
        z.output = 1;
        CHECK(std::abs(r.v[1] - bromwich(z, t)) < 1e-11 * scale);
        z.output = 2;
        CHECK(std::abs(r.storey_force[1] - bromwich(z, t)) < 1e-11 * scale);
      }
    }
  }
}

TEST_CASE("fractional rods: the output satisfies the equations of motion", "[linear_reference]") {
  const Model m = Model::Paper();
  for (bool stuck : {true, false}) {
    const Ground g = stuck ? kWeak : Ground{1.5, 1.5, 0.5};
    const LinearReference ref(m, g.u0, g.omega, g.k, stuck);
    const LinearResponse r0 = ref.at(0.0);
    CHECK(r0.x[0] == 0.0);
    CHECK(r0.v[0] == 0.0);
    // Just after the start, x ~ a_g'(0) t^3 / 6 = u0 W^3 t^3 / 6.
    const double t0 = 1e-3;
    const LinearResponse early = ref.at(t0);
    CHECK(std::abs(early.x[0]) < 1e-15 + 0.2 * g.u0 * std::pow(g.omega * t0, 3));
    CHECK(std::abs(early.v[0]) < 1e-14 + g.u0 * g.omega * std::pow(g.omega * t0, 2));
    CHECK(std::abs(early.x[1]) < 1e-15 + 0.2 * g.u0 * std::pow(g.omega * t0, 3));
    CHECK(std::abs(early.v[1]) < 1e-14 + g.u0 * g.omega * std::pow(g.omega * t0, 2));

    const double scale = g.u0 * g.omega * g.omega;
    double worst_v = 0.0, worst_a = 0.0;
    for (double t : {0.3, 1.1, 2.0, 3.7, 6.2, 9.0, 13.5, 16.0}) {
      const LinearResponse r = ref.at(t);
      auto x1 = [&](double s) { return ref.at(s).x[0]; };
      auto x2 = [&](double s) { return ref.at(s).x[1]; };
      worst_v = std::max({worst_v, std::abs(d1(x1, t, 1e-3) - r.v[0]), std::abs(d1(x2, t, 1e-3) - r.v[1])});
      double a1, a2;
      if (stuck) {
        a1 = a2 = g.ag(t) - m.rho / (m.rho + 1.0) * (r.storey_force[0] + r.storey_force[1]);
        CHECK(std::abs(r.link_force - (m.rho * r.storey_force[1] - r.storey_force[0]) / (m.rho + 1.0)) < 1e-15);
      } else {
        a1 = g.ag(t) - r.storey_force[0];
        a2 = g.ag(t) - m.rho * r.storey_force[1];
      }
      worst_a = std::max({worst_a, std::abs(d2(x1, t, 1e-2) - a1), std::abs(d2(x2, t, 1e-2) - a2)});
    }
    INFO("stuck " << stuck);
    CHECK(worst_v < 1e-9 * scale);
    CHECK(worst_a < 1e-7 * scale);
  }
}

TEST_CASE("fractional rods: the output satisfies the fractional Zener laws", "[linear_reference]") {
  // f + tau_f D^g f = k (x + tau_x D^g x), D^g by Grünwald–Letnikov on the reference's own
  // samples (first order; Richardson extrapolation over h and h/2 makes it second order).
  const Model m = Model::Paper();
  const LinearReference ref(m, kWeak.u0, kWeak.omega, kWeak.k, true);
  const double T = 2.0;
  auto residual = [&](const Rod& rod, double stiffness, bool first, std::size_t n) {
    const double h = T / static_cast<double>(n);
    std::vector<double> x(n + 1), f(n + 1), w(n + 1);
    for (std::size_t i = 0; i <= n; ++i) {
      const LinearResponse r = ref.at(h * static_cast<double>(i));
      x[i] = r.x[0];
      f[i] = first ? r.storey_force[0] : r.storey_force[1];
    }
    w[0] = 1.0;
    for (std::size_t j = 1; j <= n; ++j) w[j] = w[j - 1] * (1.0 - (rod.order + 1.0) / static_cast<double>(j));
    double dx = 0.0, df = 0.0;
    for (std::size_t j = 0; j <= n; ++j) {
      dx += w[j] * x[n - j];
      df += w[j] * f[n - j];
    }
    const double hg = std::pow(h, -rod.order);
    return f[n] + rod.tau_f * hg * df - stiffness * (x[n] + rod.tau_x * hg * dx);
  };
  for (bool first : {true, false}) {
    const Rod& rod = first ? m.rod1 : m.rod2;
    const double stiffness = first ? 1.0 : m.eps;
    const double e1 = residual(rod, stiffness, first, 500);
    const double e2 = residual(rod, stiffness, first, 1000);
    const double e3 = residual(rod, stiffness, first, 2000);
    // Richardson over h: eliminate the O(h), then the O(h^2) term.
    const double r12 = 2.0 * e2 - e1, r23 = 2.0 * e3 - e2;
    const double r = (4.0 * r23 - r12) / 3.0;
    INFO("rod " << (first ? 1 : 2) << ": " << e1 << " " << e2 << " " << e3 << " | " << r12 << " "
                << r23 << " | " << r);
    // The GL residual is first order (halves with h) and extrapolates to ~0.
    CHECK(std::abs(e3) < 0.6 * std::abs(e2));
    CHECK(std::abs(e2) < 0.6 * std::abs(e1));
    CHECK(std::abs(r) < 1e-4 * std::abs(e1));
  }
}

TEST_CASE("the paper's weak scene stays stuck", "[linear_reference]") {
  const Model m = Model::Paper();
  const LinearReference ref(m, kWeak.u0, kWeak.omega, kWeak.k, true);
  double q_max = 0.0, x_max = 0.0;
  for (int i = 0; i <= 3200; ++i) {
    const LinearResponse r = ref.at(0.005 * i);
    q_max = std::max(q_max, std::abs(r.link_force));
    x_max = std::max(x_max, std::abs(r.x[0]));
  }
  CHECK(q_max < m.mu);
  CHECK(q_max > 0.2);  // and not trivially: the stick force comes within 80% of mu
  CHECK(x_max > 0.1);
  CHECK(x_max < 0.2);
  const cplx pole = ref.natural_pole(1);
  CHECK(pole.real() < 0.0);
  CHECK(pole.imag() > 0.0);

  // Independent values: mpmath.invertlaplace (Talbot) at 50 digits on the same transforms.
  const LinearResponse r8 = ref.at(8.0), r16 = ref.at(16.0);
  CHECK(std::abs(r8.x[0] - 6.7523866352645466238e-4) < 1e-14);
  CHECK(std::abs(r8.v[0] - 2.2805633731634124691e-2) < 1e-14);
  CHECK(std::abs(r8.storey_force[0] - 1.1612697718480230187e-3) < 1e-14);
  CHECK(std::abs(r8.storey_force[1] - 1.8532703606056467753e-2) < 1e-14);
  CHECK(std::abs(r16.x[0] - 1.5037809082027091237e-3) < 1e-14);
  CHECK(std::abs(r16.v[0] - -2.2030977581248605402e-3) < 1e-14);
  CHECK(std::abs(r16.storey_force[0] - 1.3414347796847078003e-3) < 1e-14);
  CHECK(std::abs(r16.storey_force[1] - -1.2895357853677285483e-3) < 1e-14);
  CHECK(std::abs(r16.link_force - -1.324135114912381383e-3) < 1e-14);
  CHECK(std::abs(ref.at(1.122863614438693).x[0] - 0.12003723068179298997) < 1e-14);
}

TEST_CASE("linear reference rejects invalid input", "[linear_reference]") {
  Model m = Model::Paper();
  CHECK_THROWS_AS(LinearReference(m, 0.05, 0.0, 0.3, true), adjoin::InputError);
  CHECK_THROWS_AS(LinearReference(m, 0.05, 3.5, -1.0, true), adjoin::InputError);
  m.rod1.tau_x = 0.001;  // tau_x < tau_f
  CHECK_THROWS_AS(LinearReference(m, 0.05, 3.5, 0.3, true), adjoin::InputError);
  // Exact resonance: undamped oscillator driven at its natural frequency with k = 0.
  CHECK_THROWS_AS(LinearReference(elastic_model(0.5, 2.0), 0.05, 1.0, 0.0, false), adjoin::InputError);
}
