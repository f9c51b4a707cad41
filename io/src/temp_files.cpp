#include "wirerig/io/temp_files.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>

namespace wirerig {
namespace {

namespace fs = std::filesystem;

// The registry the signal handler reads: fixed storage, a slot published by its state.
enum SlotState : int { kFree = 0, kWriting = 1, kReady = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX] = {};
};
constexpr int kSlots = 32;
std::array<Slot, kSlots> g_slots;
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads these");

extern "C" void RemoveRegisteredAndReraise(int signal_number) {
  const int saved_errno = errno;
  for (Slot& slot : g_slots)
    if (slot.state.load() == kReady) ::unlink(slot.path);  // async-signal-safe
  // The default action (terminate), as if no handler had run: the exit status says SIGTERM.
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(signal_number, &action, nullptr);
  errno = saved_errno;
  ::raise(signal_number);
}

// Signals whose default action ends the process: a terminal hang-up, an interrupt, a kill or
// quit request, a timer or user signal, a write to a closed pipe, a file-size or CPU-time limit
// reached (ulimit -f, ulimit -t).
constexpr int kCleanupSignals[] = {SIGHUP,  SIGINT,  SIGTERM, SIGQUIT, SIGPIPE,
                                   SIGALRM, SIGUSR1, SIGUSR2, SIGXFSZ, SIGXCPU};

void InstallHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int signal_number : kCleanupSignals) {
      struct sigaction current {};
      if (::sigaction(signal_number, nullptr, &current) != 0) continue;
      if ((current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) continue;
      struct sigaction action {};
      action.sa_handler = RemoveRegisteredAndReraise;
      sigemptyset(&action.sa_mask);
      ::sigaction(signal_number, &action, nullptr);
    }
  });
}

// The pid of "<name>.tmp<pid>" when `entry` is a temporary file of `name`, else 0.
pid_t TemporaryPid(const std::string& entry, const std::string& name) {
  const std::string prefix = name + ".tmp";
  if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return 0;
  long pid = 0;
  for (std::size_t i = prefix.size(); i < entry.size(); ++i) {
    if (entry[i] < '0' || entry[i] > '9' || pid > 100'000'000) return 0;
    pid = pid * 10 + (entry[i] - '0');
  }
  return static_cast<pid_t>(pid);
}

}  // namespace

fs::path TemporaryPathFor(const fs::path& target) {
  return target.string() + ".tmp" + std::to_string(::getpid());
}

void RemoveStaleTemporaryFiles(const fs::path& target) {
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string name = target.filename().string();
  std::error_code error;
  fs::directory_iterator it(folder, error), end;
  for (; !error && it != end; it.increment(error)) {
    const pid_t pid = TemporaryPid(it->path().filename().string(), name);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

TemporaryFile::TemporaryFile(const fs::path& path) {
  const std::string text = path.string();
  if (text.empty() || text.size() >= PATH_MAX) return;
  InstallHandlers();
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kWriting)) {
      std::memcpy(g_slots[i].path, text.c_str(), text.size() + 1);
      g_slots[i].state.store(kReady);
      slot_ = i;
      return;
    }
  }
}

TemporaryFile::~TemporaryFile() { Keep(); }

void TemporaryFile::Keep() {
  if (slot_ < 0) return;
  g_slots[slot_].state.store(kWriting);  // the handler skips it from now on
  g_slots[slot_].path[0] = '\0';
  g_slots[slot_].state.store(kFree);
  slot_ = -1;
}

SignalsHeld::SignalsHeld() {
  static_assert(sizeof(saved_) >= sizeof(sigset_t), "room for a sigset_t");
  sigset_t held;
  sigemptyset(&held);
  for (int signal_number : kCleanupSignals) sigaddset(&held, signal_number);
  pthread_sigmask(SIG_BLOCK, &held, reinterpret_cast<sigset_t*>(saved_));
}

SignalsHeld::~SignalsHeld() {
  pthread_sigmask(SIG_SETMASK, reinterpret_cast<const sigset_t*>(saved_), nullptr);
}

}  // namespace wirerig
