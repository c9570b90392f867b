#include "common/interrupt.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>

#include "common/error.h"

namespace gearpatch::interrupt {
namespace {

namespace fs = std::filesystem;

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

struct Registry {
  std::mutex lock;
  std::set<pid_t> children;
  std::set<pid_t> stopping_themselves;  ///< children sent SIGTERM, to clean up their own children

  std::set<fs::path> scratch;
};

Registry& registry() {
  static Registry* r = new Registry;  // never destroyed: the watcher may use it during exit
  return *r;
}

int signal_pipe[2] = {-1, -1};

/// Async-signal-safe: only hands the signal number to the watcher.
extern "C" void on_signal(int sig) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(sig);
  [[maybe_unused]] ssize_t n = ::write(signal_pipe[1], &byte, 1);
  errno = saved;
}

/// Sends SIGTERM to each child that cleans up after itself and waits for
/// them all, up to ten seconds; one still running then is killed.
void stop_gently(const std::set<pid_t>& children) {
  for (pid_t pid : children) ::kill(pid, SIGTERM);
  std::set<pid_t> running = children;
  for (int tick = 0; tick < 1000 && !running.empty(); ++tick) {
    for (auto it = running.begin(); it != running.end();)
      it = ::waitpid(*it, nullptr, WNOHANG) != 0 ? running.erase(it) : std::next(it);
    if (!running.empty()) ::usleep(10000);
  }
  for (pid_t pid : running) {
    ::kill(-pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
}

/// Waits for a signal, undoes what is live, and dies of the signal. Keeps the
/// lock so that the main thread cannot spawn, reap or clean up meanwhile.
[[noreturn]] void watch() {
  unsigned char byte = 0;
  while (::read(signal_pipe[0], &byte, 1) != 1) {
  }
  const int sig = byte;
  Registry& r = registry();
  r.lock.lock();
  for (pid_t pid : r.children)
    if (!r.stopping_themselves.count(pid)) ::kill(-pid, SIGKILL);
  stop_gently(r.stopping_themselves);
  for (const fs::path& path : r.scratch) {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ::signal(sig, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);
}

void install_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe(signal_pipe) != 0) throw Error(std::string("cannot watch for signals: ") + std::strerror(errno));
    std::thread(watch).detach();
    for (int sig : kSignals) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // e.g. under nohup
      struct sigaction action {};
      action.sa_handler = on_signal;
      sigemptyset(&action.sa_mask);
      action.sa_flags = SA_RESTART;
      ::sigaction(sig, &action, nullptr);
    }
  });
}

}  // namespace

fs::path add_scratch(const std::function<fs::path()>& make) {
  install_once();
  Registry& r = registry();
  std::lock_guard guard(r.lock);
  fs::path path = make();
  r.scratch.insert(path);
  return path;
}

void drop_scratch(const fs::path& path, bool keep) {
  Registry& r = registry();
  std::lock_guard guard(r.lock);
  r.scratch.erase(path);
  std::error_code ec;
  if (!keep) fs::remove_all(path, ec);
}

pid_t add_child(const std::function<pid_t()>& spawn, bool stops_itself) {
  install_once();
  Registry& r = registry();
  std::lock_guard guard(r.lock);
  const pid_t pid = spawn();
  r.children.insert(pid);
  if (stops_itself) r.stopping_themselves.insert(pid);
  return pid;
}

std::optional<int> poll_child(pid_t pid) {
  Registry& r = registry();
  std::lock_guard guard(r.lock);
  int status = 0;
  const pid_t done = ::waitpid(pid, &status, WNOHANG);
  if (done == 0 || (done < 0 && errno == EINTR)) return std::nullopt;
  r.children.erase(pid);
  r.stopping_themselves.erase(pid);
  if (done < 0) throw Error(std::string("waiting for a child process failed: ") + std::strerror(errno));
  return status;
}

void kill_child(pid_t pid) {
  Registry& r = registry();
  std::lock_guard guard(r.lock);
  if (!r.children.count(pid)) return;
  ::kill(-pid, SIGKILL);
  while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
  }
  r.children.erase(pid);
  r.stopping_themselves.erase(pid);
}

}  // namespace gearpatch::interrupt
