#pragma once
// Probabilistic seismic demand models: ln(D) = a + b ln(IM) + e over an ensemble of ground
// motions, by least squares (GSL gsl_fit_linear), where D is a peak response of a sweep (the
// damper's stroke, a displacement, a rod force) and IM an intensity measure of the motion
// (PGA, Sa(T)). The median demand is exp(a) IM^b; the dispersion
//
//     beta = sqrt( sum e_i^2 / (n - 2) )
//
// is the standard deviation of the residuals of the log fit (n - 2 degrees of freedom, as in
// Cornell et al. 2002), and R^2 = 1 - sum e_i^2 / sum (ln D_i - mean ln D)^2.
//
//     DemandFit fit = fit_demand_model(im, demand);
//     std::vector<DemandGroupFit> fits = fit_sweep_demand(table, "drift", "pga");
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace adjoin {

struct DemandFit {
  std::size_t n = 0;
  double a = 0, b = 0;  // ln D = a + b ln IM
  double beta = 0;      // dispersion (residual standard deviation, n - 2 dof)
  double r2 = 0;        // coefficient of determination of the log fit
  double cov_aa = 0, cov_ab = 0, cov_bb = 0;  // covariance of a, b (GSL)
};

// Fits over the pairs (im[i], demand[i]); both must be positive and finite and there must be at
// least 3 pairs with at least two distinct IM values (InputError otherwise, naming what).
DemandFit fit_demand_model(std::span<const double> im, std::span<const double> demand);

// A CSV table read by header (sweep.csv).
struct SweepCsvTable {
  std::filesystem::path file;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  // Column index by name (InputError naming the file and the columns it has, if absent).
  std::size_t column(const std::string& name) const;
};
SweepCsvTable read_sweep_csv(const std::filesystem::path& file);

struct DemandGroupFit {
  std::vector<std::string> group;  // the axis values of the group (the axes' columns)
  std::size_t skipped = 0;         // rows of the group left out: failed runs, zero demand or IM
  std::size_t usable = 0;          // rows of the group that enter the fit
  // Why the group has no fit ("" if it has one: fit is then valid), e.g. fewer than 3 usable
  // motions; the other groups are still fitted.
  std::string problem;
  DemandFit fit;
};

// The columns between "index" and "motion" of a sweep table are its axes.
std::vector<std::string> sweep_axis_columns(const SweepCsvTable& table);
// IM names: "pga" (column pga_g) or "sa:T" (column sa_T, T as written in the sweep's header,
// e.g. "sa:1" for sa_1). Returns the column name.
std::string demand_im_column(const SweepCsvTable& table, const std::string& im);

// One fit per combination of the axis values (every motion of that design point), or one fit
// over all rows when the sweep has no axes or `pooled` is true. Rows with an error, or a
// non-positive demand or IM, are skipped and counted. `response` is a column name (e.g. drift).
// A group that cannot be fitted (fewer than 3 usable motions, one IM value) keeps its place with
// `problem` set; only when no group can be fitted is it an InputError (naming the table and group).
std::vector<DemandGroupFit> fit_sweep_demand(const SweepCsvTable& table, const std::string& response,
                                             const std::string& im, bool pooled = false);

}  // namespace adjoin
