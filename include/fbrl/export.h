/* SPDX-License-Identifier: MIT */
/* export.h - FBRL_API marks the library's public functions and data.
 *
 * The library is compiled with hidden visibility, so the shared library exports
 * exactly what the public headers declare with FBRL_API and nothing internal
 * (docs/abi.md). Compilers without visibility attributes get an empty FBRL_API.
 * No OS header: this compiles in a freestanding build. */
#ifndef FBRL_EXPORT_H
#define FBRL_EXPORT_H

#if defined(_WIN32) || defined(__CYGWIN__)
#if defined(FBRL_BUILDING_DLL)
#define FBRL_API __declspec(dllexport)
#elif defined(FBRL_USING_DLL)
#define FBRL_API __declspec(dllimport)
#else
#define FBRL_API
#endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#define FBRL_API __attribute__((visibility("default")))
#else
#define FBRL_API
#endif

#endif
