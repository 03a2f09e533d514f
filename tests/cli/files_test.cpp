// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// What the tool does with each kind of output target and input file (docs/cli.md, "Files, paths
// and signals"): symbolic links and directories refused, FIFOs written through, a failed run
// leaves none of its outputs, signals remove unfinished temporaries, non-regular inputs refused
// without blocking, blank sparse files refused before they are read. All in fresh temporary
// directories; FIFOs made there with mkfifo.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"

extern char** environ;

using namespace ebgeom::clitest;

namespace {

const std::string bin = EBGEOM_CLI_BINARY;
const std::string sphere = R"({"type": "sphere", "radius": 1})";

void put(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// Runs shell text `cmd`; the exit status (128 + signal when killed, as a shell reports it).
int sh(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

bool has_temporary(const std::string& dir) {
  for (const auto& n : list_dir(dir))
    if (n.find("ebgeom-tmp") != std::string::npos) return true;
  return false;
}

TEST(OutputTargets, SymbolicLinksAreRefusedAndKept) {
  const std::string dir = test_dir();
  put(dir + "/s.json", sphere);
  put(dir + "/real.npy", "old");
  ASSERT_EQ(::symlink("real.npy", (dir + "/link.npy").c_str()), 0);
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/link.npy' --res 4 -q");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("link.npy: is a symbolic link"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_symlink(dir + "/link.npy"));
  EXPECT_EQ(slurp(dir + "/real.npy"), "old");
  // --png and the .raw sidecar too.
  ASSERT_EQ(::symlink("real.npy", (dir + "/link.png").c_str()), 0);
  const RunResult p = run("sdf '" + dir + "/s.json' -o '" + dir + "/g.npy' --res 4 -q --png '" +
                          dir + "/link.png'");
  EXPECT_EQ(p.code, 4) << p.err;
  EXPECT_FALSE(exists(dir + "/g.npy"));
  ASSERT_EQ(::symlink("real.npy", (dir + "/g.json").c_str()), 0);
  const RunResult s = run("sdf '" + dir + "/s.json' -o '" + dir + "/g.raw' --res 4 -q");
  EXPECT_EQ(s.code, 4) << s.err;
  EXPECT_FALSE(exists(dir + "/g.raw"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir + "/g.json"));
  EXPECT_FALSE(has_temporary(dir));
}

TEST(OutputTargets, ADirectoryIsRefusedBeforeTheWork) {
  const std::string dir = test_dir();
  put(dir + "/s.json", sphere);
  std::filesystem::create_directory(dir + "/d.vti");
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/d.vti' --res 4 -q");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("d.vti: is a directory"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/d.vti"));
}

TEST(OutputTargets, AFifoIsWrittenThroughWithTheSameBytes) {
  const std::string dir = test_dir();
  put(dir + "/s.json", sphere);
  ASSERT_EQ(::mkfifo((dir + "/pipe.npy").c_str(), 0600), 0);
  const std::string args = "sdf '" + dir + "/s.json' --res 6 -q -o ";
  ASSERT_EQ(run(args + "'" + dir + "/file.npy'").code, 0);
  // A reader in the background copies what comes through the FIFO.
  EXPECT_EQ(sh("cat '" + dir + "/pipe.npy' > '" + dir + "/copy.npy' & timeout 60 '" + bin + "' " +
               args + "'" + dir + "/pipe.npy'; rc=$?; wait; exit $rc"),
            0);
  struct stat st;
  ASSERT_EQ(::lstat((dir + "/pipe.npy").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(slurp(dir + "/copy.npy"), slurp(dir + "/file.npy"));
  EXPECT_FALSE(has_temporary(dir));
}

TEST(OutputTargets, ALaterFailingOutputLeavesNoEarlierOne) {
  const std::string dir = test_dir();
  put(dir + "/s.json", sphere);
  // --png into a missing directory: the grid must not appear either.
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' --res 4 -q --png '" +
                          dir + "/missing/p.png'");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_FALSE(exists(dir + "/x.npy"));
  // An existing output keeps its old contents.
  put(dir + "/x.npy", "old");
  EXPECT_EQ(run("sdf '" + dir + "/s.json' -o '" + dir + "/x.npy' --res 4 -q --png '" + dir +
                "/missing/p.png'")
                .code,
            4);
  EXPECT_EQ(slurp(dir + "/x.npy"), "old");
  EXPECT_FALSE(has_temporary(dir));
}

/// Starts `ebgeom args...` without waiting; stdout and stderr go to files in `dir`.
pid_t spawn(const std::string& dir, const std::vector<std::string>& args) {
  std::vector<std::string> all{bin};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, (dir + "/stdout.txt").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, (dir + "/stderr.txt").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  if (posix_spawn(&pid, bin.c_str(), &fa, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

TEST(Signals, InterruptedRunsRemoveTheirTemporaries) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const std::string dir = test_dir() + "/" + std::to_string(sig);
    const std::string out = dir + "/out";
    std::filesystem::create_directories(out);
    put(dir + "/s.json", sphere);
    // The PNG goes to a FIFO nobody reads: the run waits there, with the grid already written to
    // its temporary (outputs are renamed only when all are written).
    ASSERT_EQ(::mkfifo((out + "/wait.png").c_str(), 0600), 0);
    const pid_t pid = spawn(dir, {"sdf", dir + "/s.json", "-o", out + "/grid.vti", "--res", "64",
                                  "-q", "--png", out + "/wait.png"});
    ASSERT_GT(pid, 0);
    bool waiting = false;
    for (int i = 0; i < 600 && !waiting; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      waiting = has_temporary(out);
      int st;
      if (!waiting && ::waitpid(pid, &st, WNOHANG) == pid) break; // ended without waiting
    }
    EXPECT_TRUE(waiting) << "signal " << sig << ": no temporary while the run waits; "
                         << slurp(dir + "/stderr.txt");
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (waiting) {
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    }
    EXPECT_EQ(list_dir(out), std::vector<std::string>{"wait.png"}) << "signal " << sig;
  }
}

TEST(InputFiles, FifosAndDevicesAreRefusedWithoutBlocking) {
  const std::string dir = test_dir();
  ASSERT_EQ(::mkfifo((dir + "/in.stl").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir + "/pts.npy").c_str(), 0600), 0);
  put(dir + "/good.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  // Each would wait forever for a writer (or, for /dev/null, be called empty); `timeout` turns a
  // hang into a failure.
  const std::string t = "timeout 30 '" + bin + "' ";
  const std::string err = "'" + dir + "/err.txt'";
  for (const std::string& cmd :
       {"info '" + dir + "/in.stl'", "sdf '" + dir + "/in.stl' -o '" + dir + "/o.npy' --res 4 -q",
        "convert '" + dir + "/in.stl' '" + dir + "/o.ply'",
        "query '" + dir + "/good.obj' --points '" + dir + "/pts.npy' -o '" + dir + "/d.npy'",
        std::string("info /dev/null")}) {
    EXPECT_EQ(sh(t + cmd + " </dev/null >'" + dir + "/out.txt' 2>" + err), 3) << cmd;
    const std::string e = slurp(dir + "/err.txt");
    EXPECT_NE(e.find("not a regular file"), std::string::npos) << cmd << ": " << e;
  }
  EXPECT_NE(slurp(dir + "/err.txt").find("/dev/null: is a character device"), std::string::npos);
  // A mesh named inside a scene goes through the library's reader: refused there too.
  put(dir + "/scene.json", R"({"type": "mesh", "path": "in.stl"})");
  EXPECT_EQ(sh(t + "sdf '" + dir + "/scene.json' -o '" + dir + "/o.npy' --res 4 -q 2>" + err), 3);
  EXPECT_NE(slurp(dir + "/err.txt").find("is a FIFO (named pipe), not a regular file"),
            std::string::npos)
      << slurp(dir + "/err.txt");
}

TEST(InputFiles, ABlankSparseFileIsRefusedBeforeItIsRead) {
  const std::string dir = test_dir();
  const std::string big = dir + "/big.stl";
  {
    const int fd = ::open(big.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    const bool sized = ::ftruncate(fd, off_t(8) << 30) == 0; // 8 GiB of holes
    ::close(fd);
    if (!sized) GTEST_SKIP() << "this file system cannot hold an 8 GiB sparse file";
  }
  struct stat st;
  ASSERT_EQ(::stat(big.c_str(), &st), 0);
  if (std::uint64_t(st.st_blocks) * 512 > (1u << 20)) GTEST_SKIP() << "not sparse here";
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(sh("timeout 60 '" + bin + "' info '" + big + "' 2>'" + dir + "/err.txt'"), 3);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, 10.0);
  const std::string e = slurp(dir + "/err.txt");
  EXPECT_NE(e.find("big.stl: byte 0: the first 65536 of its 8589934592 bytes are all zero"),
            std::string::npos)
      << e;
}

} // namespace
