// SPDX-License-Identifier: MIT
// printf-style formatting into a std::string, for the baker's summaries, reports and tables; the
// compiler checks each call's arguments against its format.
#pragma once

#include <string>

#if defined(__GNUC__)
#define PRT_BAKE_PRINTF_LIKE __attribute__((format(printf, 1, 2)))
#else
#define PRT_BAKE_PRINTF_LIKE
#endif

namespace prt::bake {

std::string format(const char* fmt, ...) PRT_BAKE_PRINTF_LIKE;

}  // namespace prt::bake
