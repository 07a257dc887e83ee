#pragma once
/// @file realtime.hpp
/// The real-time contract as a mark the build checks. A function declared HAPTICCTRL_RT may be
/// called from a cycle: it allocates nothing, takes no blocking lock, throws nothing and does no
/// I/O but wake/notify, and it calls only functions that are marked too (or standard and Eigen
/// functions outside the check's list of those that allocate, lock, throw or do I/O).
/// scripts/check_realtime.py reads the AST of the core's sources through libclang and fails,
/// naming the call, when a marked function breaks this (docs/architecture.md, *The real-time
/// contract*).
///
/// The mark is a clang annotation, seen only when clang parses the code (the check); GCC
/// builds see nothing. Put it first on a function's declaration (and on its definition when that
/// is the only declaration): `HAPTICCTRL_RT void step(double dt) noexcept;`.

#if defined(__clang__)
#define HAPTICCTRL_RT [[clang::annotate("hapticctrl::rt")]]
#else
#define HAPTICCTRL_RT
#endif
