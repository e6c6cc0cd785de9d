# SPDX-License-Identifier: BSD-3-Clause
# cmake -DINPUT=<file> -DOUTPUT=<source.cpp> -DSYMBOL=<name> -P EmbedFile.cmake
# Writes a C++ source defining `const unsigned char lic3d::<SYMBOL>[]` with the file's bytes and
# `const std::size_t lic3d::<SYMBOL>Size`: every byte a hex escape of a string literal, 32 to a
# line, which compiles in a fraction of the time of an initializer list of numbers.
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" digits)
math(EXPR size "${digits} / 2")
string(REPEAT "[0-9a-f]" 64 line)
string(REGEX REPLACE "(${line})" "\\1\n" lines "${hex}")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "\\\\x\\1" escaped "${lines}")
string(REPLACE "\n" "\"\n    \"" quoted "${escaped}")
file(WRITE "${OUTPUT}.tmp"
     "// Generated from ${INPUT} by cmake/EmbedFile.cmake: do not edit.\n"
     "#include <cstddef>\n\nnamespace lic3d {\n\n"
     "extern const unsigned char ${SYMBOL}[];\n"
     "extern const std::size_t ${SYMBOL}Size;\n"
     "alignas(4) const unsigned char ${SYMBOL}[] =\n    \"${quoted}\";\n"
     "const std::size_t ${SYMBOL}Size = ${size};\n\n}  // namespace lic3d\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
