# SPDX-License-Identifier: GPL-3.0-or-later
# Writes OUT, a header that names the commit arcpress is built from (`git describe --always
# --dirty`; "unknown" outside a git checkout), only when that changes, so that --version is
# right after every commit without rebuilding what does not use it.
#   cmake -DSOURCE=DIR -DOUT=FILE -P commit.cmake
execute_process(COMMAND git -C "${SOURCE}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR commit STREQUAL "")
  set(commit "unknown")
endif()
file(WRITE "${OUT}.new" "// Written by cmake/commit.cmake.\n#pragma once\n#define ARCPRESS_COMMIT \"${commit}\"\n")
file(COPY_FILE "${OUT}.new" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.new")
