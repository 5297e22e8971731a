# SPDX-License-Identifier: MIT
# Turns a SPIR-V file into a C++ header with a uint32_t array, so the viewer
# carries its shaders inside the binary. -DSPV=in.spv -DHEADER=out.h -DNAME=kName
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" length)
math(EXPR words "${length} / 8")
set(body "")
set(i 0)
while(i LESS length)
  # SPIR-V words are little-endian: reverse the bytes of each group of four.
  string(SUBSTRING "${hex}" ${i} 8 w)
  string(SUBSTRING "${w}" 0 2 b0)
  string(SUBSTRING "${w}" 2 2 b1)
  string(SUBSTRING "${w}" 4 2 b2)
  string(SUBSTRING "${w}" 6 2 b3)
  string(APPEND body "0x${b3}${b2}${b1}${b0}u,")
  math(EXPR i "${i} + 8")
  math(EXPR col "${i} % 64")
  if(col EQUAL 0)
    string(APPEND body "\n")
  endif()
endwhile()
file(WRITE ${HEADER} "// Generated from ${SPV} by cmake/embed_spirv.cmake.\n#pragma once\n#include <cstdint>\n"
                     "inline constexpr std::uint32_t ${NAME}[] = {\n${body}};\n")
