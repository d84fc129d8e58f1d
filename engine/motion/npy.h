// NumPy arrays: .npy files, the members of .npz archives (a zip of .npy files, engine/motion/zip.h),
// the layer under engine/motion/npz.h. Only what motion files need: little-endian float and
// integer arrays in C order, and scalar text for writing.
//
// Reading is strict and bounded: the header is a Python dict literal with exactly the keys
// 'descr', 'fortran_order' and 'shape'; the data must have exactly the size the shape says; an
// archive member's declared size is checked against the archive's size before anything is
// allocated. Every problem is a gmg::Error naming the archive and the array ("x.npz: poses.npy:
// ...").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gmg {

// One numeric array, its values converted to double (exact for every accepted dtype except
// integers beyond 2^53, which motion files do not hold).
struct NpyArray {
  std::string dtype;                 // "<f8", "<f4", "<i8" or "<i4", as the header gave it
  std::vector<std::uint64_t> shape;  // empty for a scalar (shape ())
  std::vector<double> values;        // C order; as many as the product of shape (1 for a scalar)
};

// Parses the bytes of one .npy file (format versions 1, 2 and 3). `name` labels errors
// ("x.npz: poses.npy"). Rejects a bad magic or version, a header that is not the dict numpy
// writes, another dtype (big-endian, text, object, structured), Fortran order with more than one
// dimension, and data shorter or longer than the shape needs. NaN and infinite values are kept:
// the caller decides what they mean.
NpyArray npy_parse(std::string_view bytes, const std::string& name);

// The text of a one-element text array (dtype "<U<length>", UTF-32, as numpy saves a str), its
// trailing NULs dropped. Only printable ASCII is accepted (SMPL-X archives hold "neutral",
// "smplx2020"); another dtype, shape or character is a gmg::Error naming `name`.
std::string npy_parse_text(std::string_view bytes, const std::string& name);

// The .npy bytes (format 1.0, header padded to 64 bytes as numpy pads it) of a C-order array.
// dtype "<f8" writes the values as doubles, "<f4" as floats (rounded to nearest; a finite value
// beyond float32's range is an error), "<i4" as 32-bit integers (values must be whole and in
// range).
std::string npy_format(const std::string& dtype, const std::vector<std::uint64_t>& shape,
                       const std::vector<double>& values);

// The .npy bytes of a 0-d text array (dtype "<U<len>", UTF-32), as numpy saves a str. ASCII only.
std::string npy_format_text(const std::string& text);

}  // namespace gmg
