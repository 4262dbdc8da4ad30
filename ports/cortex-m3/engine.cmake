# SPDX-License-Identifier: MIT
# The language engine's compile-time options for the Cortex-M3 firmware's 64 KB of RAM
# (docs/firmware.md, "Engine options the firmware uses"): no HELP texts, headers that point
# at their names, the primitives' headers in flash, 256-byte lines, 4 nested sources, short
# paths, a small REQUIRE list, 3 S" buffers, a 64-entry table of source
# lines for error positions (the board reads no source files; past it, a line falls back to
# its word's line), a 2 KB heap, 4 tasks, no FILE word set
# (no file system), no transcendental FLOATING-EXT words but those calibration uses, and no
# word hook (a debugger's single steps: the board has none). Used by
# ports/cortex-m3/CMakeLists.txt and, on the host, by tests/qemu/cm3_engine.cmake (the Forth
# conformance suite with the same options).
set(FBRL_CM3_ENGINE_DEFS FBRL_NO_HELP FBRL_SMALL_HEADERS FBRL_ROM_PRIMS FBRL_LINE_MAX=256 FBRL_SRC_MAX=4
  FBRL_PATH_MAX=32 FBRL_REQ_POOL=256 FBRL_NSBUF=3 FBRL_LINE_TABLE=64
  FBRL_STACK_ALIGN=16 FBRL_HEAP_MAX=2048 FBRL_LOCALS_MAX=64 FBRL_TASKS_MAX=4
  FBRL_WL_MAX=8 FBRL_FILES_MAX=2 FBRL_NO_FILE_WORDS FBRL_NO_FTRANS FBRL_NO_WORD_HOOK)
