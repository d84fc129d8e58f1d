// Test data shared by the text module's tests: a TextGrid in Praat's long format, UTF-16
// encoding.
#pragma once

#include <string>

namespace gmg::testing {

// Encodes ASCII/UTF-8-free text as UTF-16 with a byte-order mark.
inline std::string to_utf16(const std::string& ascii, bool little_endian) {
  std::string out = little_endian ? std::string("\xFF\xFE", 2) : std::string("\xFE\xFF", 2);
  for (char c : ascii) {
    if (little_endian) {
      out += c;
      out += '\0';
    } else {
      out += '\0';
      out += c;
    }
  }
  return out;
}

// Praat long format: a "phones" tier, then a "words" tier of five intervals ("" and "   " are
// silence; the last holds Praat's doubled quotes). Line numbers matter to the tests: interval 2
// of the words tier has its xmax on line 35, interval 4 on line 43.
inline const char* const kLongTextGrid =
    "File type = \"ooTextFile\"\n"
    "Object class = \"TextGrid\"\n"
    "\n"
    "xmin = 0 \n"
    "xmax = 3.5 \n"
    "tiers? <exists> \n"
    "size = 2 \n"
    "item []: \n"
    "    item [1]:\n"
    "        class = \"IntervalTier\" \n"
    "        name = \"phones\" \n"
    "        xmin = 0 \n"
    "        xmax = 3.5 \n"
    "        intervals: size = 2 \n"
    "        intervals [1]:\n"
    "            xmin = 0 \n"
    "            xmax = 1 \n"
    "            text = \"\" \n"
    "        intervals [2]:\n"
    "            xmin = 1 \n"
    "            xmax = 3.5 \n"
    "            text = \"AH0\" \n"
    "    item [2]:\n"
    "        class = \"IntervalTier\" \n"
    "        name = \"words\" \n"
    "        xmin = 0 \n"
    "        xmax = 3.5 \n"
    "        intervals: size = 5 \n"
    "        intervals [1]:\n"
    "            xmin = 0 \n"
    "            xmax = 1 \n"
    "            text = \"\" \n"
    "        intervals [2]:\n"
    "            xmin = 1 \n"
    "            xmax = 1.5 \n"
    "            text = \"very\" \n"
    "        intervals [3]:\n"
    "            xmin = 1.5 \n"
    "            xmax = 2 \n"
    "            text = \"   \" \n"
    "        intervals [4]:\n"
    "            xmin = 2 \n"
    "            xmax = 2.25 \n"
    "            text = \"big\" \n"
    "        intervals [5]:\n"
    "            xmin = 2.25 \n"
    "            xmax = 3.5 \n"
    "            text = \"say \"\"hi\"\"\" \n";

}  // namespace gmg::testing
