#pragma once
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>

namespace gearpatch::interrupt {

/// What an interrupted run must undo, kept while it is live: the process
/// groups of running children, scratch folders and staged output files. On
/// SIGINT, SIGTERM or SIGHUP a watcher thread kills every group (or stops it, below), removes every
/// scratch path and then ends the program by that same signal (a shell sees
/// 128 + n). A signal the program was started with ignored stays ignored.
///
/// Every change to the registry and every reap happens under one lock that
/// the watcher takes for good, so nothing is spawned, reaped or reported
/// after an interrupt has begun.

/// Makes a scratch folder or file with `make` (which returns its path) and
/// registers it.
std::filesystem::path add_scratch(const std::function<std::filesystem::path()>& make);

/// Unregisters a scratch path, and removes it from disk unless `keep`.
void drop_scratch(const std::filesystem::path& path, bool keep);

/// Starts a child with `spawn` (which returns its pid, the leader of its own
/// process group) and registers the group. A child that `stops_itself` (a
/// gearpatch worker with an ngspice and a scratch folder of its own) is sent
/// SIGTERM on an interrupt and waited for (up to 10 s) instead of killed, so
/// that it undoes what it started.
pid_t add_child(const std::function<pid_t()>& spawn, bool stops_itself = false);

/// The child's wait status once it has ended (then it is unregistered),
/// nothing while it runs.
std::optional<int> poll_child(pid_t pid);

/// Kills the child's whole process group and reaps the child.
void kill_child(pid_t pid);

}  // namespace gearpatch::interrupt
