// libFuzzer harness: config files (engine/config/config.cpp): JSON parsing, every key's setter and
// the validation of the result.
#include "engine/config/config.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error("fuzz.json", [&] {
    gmg::Config c;
    gmg::config_load_text(c, gmg::fuzz::bytes_of(data, size), "fuzz.json");
    gmg::config_validate(c);
    // What validates must print and read back.
    gmg::Config back;
    gmg::config_load_text(back, gmg::config_to_json(c), "fuzz.json");
    if (gmg::config_to_json(back) != gmg::config_to_json(c)) std::abort();
  });
  return 0;
}
