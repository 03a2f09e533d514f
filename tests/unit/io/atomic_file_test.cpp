// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// AtomicFile and OutputGroup: what each kind of output target gets (regular file, missing file,
// symbolic link, FIFO, directory), unique no-follow temporaries with the target's permissions,
// deferred renames of a group, and removal of temporaries on signals. Everything happens in a
// fresh temporary directory; FIFOs are made there with mkfifo.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "ebgeom/eval/write_grid.hpp"
#include "ebgeom/io/atomic_file.hpp"

namespace {

namespace fs = std::filesystem;
using ebgeom::AtomicFile;
using ebgeom::OutputGroup;

struct TempDir {
  std::string path;
  TempDir() {
    std::string t = fs::temp_directory_path().string() + "/ebgeom_atomic_XXXXXX";
    std::vector<char> b(t.begin(), t.end());
    b.push_back('\0');
    path = ::mkdtemp(b.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return path + "/" + name; }
  std::vector<std::string> names() const {
    std::vector<std::string> r;
    for (const auto& e : fs::directory_iterator(path)) r.push_back(e.path().filename().string());
    std::sort(r.begin(), r.end());
    return r;
  }
};

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void spit(const std::string& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

ebgeom::Result<ebgeom::Ok> write_text(const std::string& path, const std::string& text) {
  AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  f.stream() << text;
  return f.commit();
}

TEST(AtomicFile, CreatesAndReplacesRegularFilesLeavingNoTemporary) {
  TempDir d;
  ASSERT_TRUE(write_text(d / "a.txt", "first"));
  EXPECT_EQ(slurp(d / "a.txt"), "first");
  ASSERT_TRUE(write_text(d / "a.txt", "second"));
  EXPECT_EQ(slurp(d / "a.txt"), "second");
  EXPECT_EQ(d.names(), std::vector<std::string>{"a.txt"});
}

TEST(AtomicFile, ReplacedFileKeepsItsPermissionBits) {
  TempDir d;
  spit(d / "p.txt", "old");
  ASSERT_EQ(::chmod((d / "p.txt").c_str(), 0640), 0);
  ASSERT_TRUE(write_text(d / "p.txt", "new"));
  struct stat st;
  ASSERT_EQ(::stat((d / "p.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  ASSERT_EQ(::chmod((d / "p.txt").c_str(), 0600), 0);
  ASSERT_TRUE(write_text(d / "p.txt", "newer"));
  ASSERT_EQ(::stat((d / "p.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  // A new file gets 0666 less the umask.
  const mode_t mask = ::umask(022);
  ::umask(mask);
  ASSERT_TRUE(write_text(d / "fresh.txt", "x"));
  ASSERT_EQ(::stat((d / "fresh.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0666u & ~mask);
}

TEST(AtomicFile, TemporariesAreUniqueAndNeverFollowAPlantedLink) {
  TempDir d;
  const std::string out = d / "out.npy";
  spit(d / "victim.txt", "precious");
  // The fixed temporary name of earlier versions, planted as a link to another file.
  ASSERT_EQ(::symlink((d / "victim.txt").c_str(), (out + ".ebgeom-tmp").c_str()), 0);
  AtomicFile a(out), b(out);
  ASSERT_TRUE(a.is_open());
  ASSERT_TRUE(b.is_open());
  EXPECT_NE(a.temp_path(), b.temp_path());
  EXPECT_EQ(fs::path(a.temp_path()).parent_path(), fs::path(out).parent_path());
  a.stream() << "from a";
  b.stream() << "from b";
  ASSERT_TRUE(a.commit());
  EXPECT_EQ(slurp(out), "from a");
  ASSERT_TRUE(b.commit());
  EXPECT_EQ(slurp(out), "from b");
  EXPECT_EQ(slurp(d / "victim.txt"), "precious");
  EXPECT_TRUE(fs::is_symlink(out + ".ebgeom-tmp"));
}

TEST(AtomicFile, SymbolicLinksAreRefusedAndLeftAlone) {
  TempDir d;
  spit(d / "real.txt", "real");
  ASSERT_EQ(::symlink("real.txt", (d / "link.txt").c_str()), 0);
  ASSERT_EQ(::symlink("missing.txt", (d / "dangling.txt").c_str()), 0);
  for (const std::string name : {"link.txt", "dangling.txt"}) {
    auto r = write_text(d / name, "new");
    ASSERT_FALSE(r) << name;
    EXPECT_EQ(r.error().code, ebgeom::ErrorCode::io);
    EXPECT_NE(r.error().what().find("symbolic link"), std::string::npos) << r.error().what();
    EXPECT_TRUE(fs::is_symlink(d / name));
  }
  EXPECT_EQ(slurp(d / "real.txt"), "real");
  EXPECT_EQ(d.names(), (std::vector<std::string>{"dangling.txt", "link.txt", "real.txt"}));
}

TEST(AtomicFile, DirectoriesAreRefused) {
  TempDir d;
  fs::create_directory(d / "sub.vti");
  auto r = write_text(d / "sub.vti", "x");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().what().find("is a directory"), std::string::npos) << r.error().what();
  EXPECT_TRUE(fs::is_directory(d / "sub.vti"));
}

TEST(AtomicFile, FifosAreWrittenThroughNotReplaced) {
  TempDir d;
  const std::string fifo = d / "pipe.npy";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A reader first (non-blocking), so the writer's open does not wait.
  const int rd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(rd, 0);
  auto r = write_text(fifo, "through the pipe");
  EXPECT_TRUE(r) << (r ? "" : r.error().what());
  char buf[64] = {};
  const ssize_t n = ::read(rd, buf, sizeof buf);
  ::close(rd);
  EXPECT_EQ(std::string(buf, n > 0 ? std::size_t(n) : 0), "through the pipe");
  struct stat st;
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(d.names(), std::vector<std::string>{"pipe.npy"});
  // Also through a link to it.
  ASSERT_EQ(::symlink("pipe.npy", (d / "to_pipe").c_str()), 0);
  EXPECT_EQ(ebgeom::check_output_target(d / "to_pipe").value(), ebgeom::OutputTargetKind::stream);
}

TEST(OutputGroup, OutputsAppearOnlyWhenTheGroupCommits) {
  TempDir d;
  {
    OutputGroup g;
    ASSERT_TRUE(write_text(d / "a.txt", "a"));
    ASSERT_TRUE(write_text(d / "b.txt", "b"));
    EXPECT_FALSE(fs::exists(d / "a.txt"));
    EXPECT_FALSE(fs::exists(d / "b.txt"));
    ASSERT_TRUE(g.commit());
  }
  EXPECT_EQ(slurp(d / "a.txt"), "a");
  EXPECT_EQ(slurp(d / "b.txt"), "b");
  EXPECT_EQ(d.names(), (std::vector<std::string>{"a.txt", "b.txt"}));
}

TEST(OutputGroup, ALaterFailureLeavesNoEarlierOutput) {
  TempDir d;
  spit(d / "keep.npy", "old contents");
  {
    OutputGroup g;
    std::vector<float> v(8, 1.0f);
    ASSERT_TRUE(ebgeom::write_npy(d / "keep.npy", ebgeom::Span<const float>(v), {8}));
    ASSERT_TRUE(write_text(d / "new.txt", "new"));
    EXPECT_FALSE(write_text(d / "missing-dir/c.png", "c")); // the job fails here
  }
  EXPECT_EQ(slurp(d / "keep.npy"), "old contents");
  EXPECT_EQ(d.names(), std::vector<std::string>{"keep.npy"});
}

TEST(AtomicFile, SignalsRemoveUnfinishedTemporaries) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    TempDir d;
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::signal(sig, SIG_DFL);
      ebgeom::remove_temp_files_on_signals();
      OutputGroup g;
      AtomicFile committed(d / "pending.txt");
      committed.stream() << "pending in the group";
      if (!committed.commit()) ::_exit(10);
      AtomicFile open(d / "open.txt");
      open.stream() << std::string(1 << 20, 'x');
      open.stream().flush();
      ::raise(sig);
      ::_exit(11); // not reached
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << sig << ", status " << status;
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_TRUE(d.names().empty())
        << "signal " << sig << " left " << d.names().size() << " files, e.g. " << d.names()[0];
  }
}

} // namespace
