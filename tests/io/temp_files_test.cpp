// Temporary files: SIGINT, SIGTERM and the other terminating signals remove the registered ones and
// still end the process by that signal; a stale temporary file of a dead process is removed by the
// next write beside its target, a live process's is kept.
#include "wirerig/io/temp_files.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "wirerig/io/atomic_file.h"

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path ScratchDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("wirerig_temp_files_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void Touch(const fs::path& path) { std::ofstream(path) << "x"; }

// A pid that was just used by a process which has exited (and been reaped).
pid_t DeadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

TEST(TemporaryFiles, PathCarriesThePid) {
  EXPECT_EQ(TemporaryPathFor("a/out.glb").string(), "a/out.glb.tmp" + std::to_string(::getpid()));
}

TEST(TemporaryFiles, StaleOnesOfDeadProcessesAreRemoved) {
  const fs::path dir = ScratchDir("stale");
  const std::string dead = std::to_string(DeadPid());
  const std::string alive = std::to_string(::getppid());
  for (const std::string& name : std::vector<std::string>{
           "out.glb", "out.glb.tmp" + dead, "out.glb.tmp" + alive,
           "out.glb.tmp" + std::to_string(::getpid()), "out.glb.tmpx1", "other.glb.tmp" + dead})
    Touch(dir / name);
  RemoveStaleTemporaryFiles(dir / "out.glb");
  EXPECT_FALSE(fs::exists(dir / ("out.glb.tmp" + dead)));
  for (const std::string& name : std::vector<std::string>{
           "out.glb", "out.glb.tmp" + alive, "out.glb.tmp" + std::to_string(::getpid()),
           "out.glb.tmpx1", "other.glb.tmp" + dead})
    EXPECT_TRUE(fs::exists(dir / name)) << name;
}

TEST(TemporaryFiles, TheNextAtomicWriteRemovesAStaleOne) {
  const fs::path dir = ScratchDir("next_write");
  const fs::path stale = dir / ("out.json.tmp" + std::to_string(DeadPid()));
  Touch(stale);
  ASSERT_TRUE(WriteFileAtomically(dir / "out.json", "{}").ok());
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(dir / "out.json"));
}

// In a child: registers `file` (and a kept one), then raises `signal_number`.
void ExpectSignalRemoves(int signal_number) {
  const fs::path dir = ScratchDir("signal" + std::to_string(signal_number));
  const fs::path file = dir / "out.glb.tmp1", kept = dir / "kept.glb";
  Touch(file);
  Touch(kept);
  const pid_t pid = ::fork();
  if (pid == 0) {
    TemporaryFile registered(file);
    TemporaryFile renamed(kept);
    renamed.Keep();
    ::raise(signal_number);
    ::_exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), signal_number);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::exists(kept));
}

TEST(TemporaryFiles, SigtermRemovesRegisteredFilesAndStillKills) { ExpectSignalRemoves(SIGTERM); }
TEST(TemporaryFiles, SigintRemovesRegisteredFilesAndStillKills) { ExpectSignalRemoves(SIGINT); }
// A hang-up (a closed terminal), a quit, a broken pipe, a timer, a user signal or a file-size
// or CPU-time limit (a bake under `ulimit -f`) left the temporary file behind until the next run.
TEST(TemporaryFiles, EveryTerminatingSignalRemovesRegisteredFiles) {
  for (int signal_number :
       {SIGHUP, SIGQUIT, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2, SIGXFSZ, SIGXCPU}) {
    SCOPED_TRACE(signal_number);
    ExpectSignalRemoves(signal_number);
  }
}

// Steps that must not be split by a kill: a signal raised while held arrives after them.
TEST(TemporaryFiles, SignalsHeldArriveAfterTheHeldSteps) {
  const fs::path dir = ScratchDir("held");
  const fs::path file = dir / "out.bin", done = dir / "done";
  Touch(file);
  fs::remove(done);
  const pid_t pid = ::fork();
  if (pid == 0) {
    TemporaryFile registered(file);
    {
      const SignalsHeld held;
      ::raise(SIGTERM);
      Touch(done);        // reached: the signal waits
      registered.Keep();  // and the file is no longer covered when it comes
    }
    ::_exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(fs::exists(done));
  EXPECT_TRUE(fs::exists(file));
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
