// The shipped keyword lexicon (assets/keywords.txt) as text compiled into the binary. The build
// generates its definition from the asset file, so editing assets/keywords.txt and rebuilding is
// all it takes to change the default.
#pragma once

namespace gmg::text {

extern const char* const kDefaultLexiconText;  // UTF-8, the asset file's bytes
extern const char* const kDefaultLexiconName;  // "assets/keywords.txt" (for messages)

}  // namespace gmg::text
