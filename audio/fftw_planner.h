// FFTW's planner is not thread-safe: every FFTW plan gmg makes is made under this one lock (plans
// are made once per process and then executed on other arrays from any thread, which is safe).
#pragma once

#include <mutex>

namespace gmg::audio {

std::mutex& fftw_planner_mutex();

}  // namespace gmg::audio
