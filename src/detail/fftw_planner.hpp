#pragma once
// FFTW's planner (plan creation and destruction) is one global, non-thread-safe state shared
// by every module that plans transforms; executing a plan is thread-safe. Every fftw_plan_* and
// fftw_destroy_plan call in adjoin holds this one mutex, so sweeps that run simulations,
// spectra and syntheses on several threads never plan concurrently.
#include <mutex>

namespace adjoin::detail {

std::mutex& fftw_planner_mutex();

}  // namespace adjoin::detail
