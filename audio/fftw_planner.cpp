#include "audio/fftw_planner.h"

namespace gmg::audio {

std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace gmg::audio
