// The control of upward_include.cpp: the same include context with only declared dependencies
// (audio/ may use engine/core/) builds. So the upward test fails for the include alone.
#include "audio/wav.h"
#include "engine/core/error.h"

int gmg_layering_allowed() { return static_cast<int>(gmg::audio::Audio{}.duration()); }
