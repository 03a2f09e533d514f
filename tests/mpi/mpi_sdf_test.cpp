// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `mpirun -n P ebgeom-mpi sdf` against the serial `ebgeom sdf`: for 1, 2 and 4 ranks, dense and
// narrow band, the .npy and .raw files are identical byte for byte and the .pvti pieces,
// reassembled, hold the serial .vti's values bit for bit. Unreadable inputs and unwritable outputs
// end every rank with one error message and the serial tool's exit code, within a timeout.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "ebgeom/mesh/generate.hpp"

using namespace ebgeom;
using namespace ebgeom::clitest;

namespace {

/// Runs `mpirun -n ranks ebgeom-mpi ARGS` under a timeout (exit code 124 if it hangs). Under
/// LeakSanitizer (the asan preset), Open MPI's own leaks at exit are suppressed by
/// tests/mpi/lsan_openmpi.supp; full stack unwinding on malloc (Open MPI's libraries lack frame
/// pointers) and plugins kept loaded let the suppressions see Open MPI's frames. Leaks with no
/// Open MPI frame are still reported.
RunResult run_mpi(int ranks, const std::string& args) {
  static int counter = 0;
  const std::string base = ::testing::TempDir() + "ebgeom_mpi_run" + std::to_string(::getpid()) +
                           "_" + std::to_string(++counter);
  const std::string cmd =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
      "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}fast_unwind_on_malloc=0\" "
      "LSAN_OPTIONS=\"${LSAN_OPTIONS:+$LSAN_OPTIONS:}suppressions=" EBGEOM_SOURCE_DIR
      "/tests/mpi/lsan_openmpi.supp:print_suppressions=0\" "
      "OMPI_MCA_mca_base_component_disable_dlclose=1 timeout 120 '" +
      std::string(EBGEOM_MPIEXEC) + "' " + EBGEOM_MPIEXEC_FLAGS + " -n " + std::to_string(ranks) +
      " '" + EBGEOM_MPI_BINARY + "' " + args + " </dev/null >'" + base + ".out' 2>'" + base +
      ".err'";
  const int st = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

/// A closed torus mesh as an OBJ file (the same file for the serial and distributed runs).
std::string torus_obj(const std::string& dir) {
  const auto soup = make_torus<double>(1.0, 0.35, 40, 20).value();
  const std::string path = dir + "/torus.obj";
  std::ofstream out(path);
  out.precision(17);
  for (const auto& v : soup.vertices) out << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    out << 'f';
    for (auto i = soup.offsets[f]; i < soup.offsets[f + 1]; ++i) out << ' ' << soup.indices[i] + 1;
    out << '\n';
  }
  return path;
}

std::string scene_path() { return std::string(EBGEOM_SOURCE_DIR) + "/examples/scenes/csg.json"; }

/// One .vti piece of a .pvti: values over `Extent` (global indices, inclusive).
struct Piece {
  int extent[6] = {0, 0, 0, 0, 0, 0};
  std::string type;
  std::string bytes; // raw values, x fastest
};

Piece read_piece(const std::string& path) {
  Piece p;
  const std::string b = slurp(path);
  const auto app = b.find("<AppendedData encoding=\"raw\">");
  if (app == std::string::npos) {
    ADD_FAILURE() << path << ": no appended data";
    return p;
  }
  const std::string head = b.substr(0, app);
  const auto piece = head.find("<Piece ");
  std::istringstream(xml_attr(head.substr(piece), "Extent")) >> p.extent[0] >> p.extent[1] >>
      p.extent[2] >> p.extent[3] >> p.extent[4] >> p.extent[5];
  p.type = xml_attr(head.substr(head.find("<DataArray")), "type");
  const auto us = b.find('_', app);
  std::uint64_t nbytes = 0;
  std::memcpy(&nbytes, b.data() + us + 1, 8);
  p.bytes = b.substr(us + 9, nbytes);
  EXPECT_EQ(p.bytes.size(), nbytes) << path;
  return p;
}

/// Reassembles `OUT.pvti` into the raw bytes of a whole grid (x fastest); checks that the pieces
/// cover every sample and agree where they overlap.
std::string reassemble(const std::string& pvti, const int (&dims)[3], std::size_t width) {
  const std::string text = slurp(pvti);
  EXPECT_NE(text.find("<VTKFile type=\"PImageData\""), std::string::npos);
  const std::string dir = std::filesystem::path(pvti).parent_path().string();
  const std::size_t samples = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::string grid(samples * width, '\0');
  std::vector<char> seen(samples, 0);
  const std::regex piece_re("<Piece Extent=\"([0-9 ]+)\" Source=\"([^\"]+)\"/>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), piece_re);
       it != std::sregex_iterator(); ++it) {
    const Piece p = read_piece(dir + "/" + (*it)[2].str());
    int e[6];
    std::istringstream((*it)[1].str()) >> e[0] >> e[1] >> e[2] >> e[3] >> e[4] >> e[5];
    for (int a = 0; a < 6; ++a) EXPECT_EQ(e[a], p.extent[a]) << (*it)[2];
    const int nx = e[1] - e[0] + 1, ny = e[3] - e[2] + 1;
    for (int k = e[4]; k <= e[5]; ++k)
      for (int j = e[2]; j <= e[3]; ++j)
        for (int i = e[0]; i <= e[1]; ++i) {
          const std::size_t g = std::size_t(i) + dims[0] * (std::size_t(j) + dims[1] * k);
          const std::size_t l =
              std::size_t(i - e[0]) + nx * (std::size_t(j - e[2]) + ny * (k - e[4]));
          const std::string v = p.bytes.substr(l * width, width);
          if (seen[g]) {
            EXPECT_EQ(grid.substr(g * width, width), v) << "overlap at " << g;
          }
          grid.replace(g * width, width, v);
          seen[g] = 1;
        }
  }
  for (std::size_t g = 0; g < seen.size(); ++g)
    EXPECT_TRUE(seen[g]) << "sample " << g << " missing";
  return grid;
}

struct Case {
  const char* name;
  bool mesh;        // torus OBJ, else the csg.json scene
  const char* ext;  // .npy, .raw or .pvti (the serial run writes .vti for the last)
  const char* opts; // grid options shared by both runs
};

const Case cases[] = {
    {"mesh_dense_npy", true, ".npy", "--res 37 41 29"},
    {"mesh_band_npy", true, ".npy", "--res 48 --band 2"},
    {"mesh_band_double_raw", true, ".raw", "--res 40 --band 3 --precision double --nodes"},
    {"scene_dense_raw", false, ".raw", "--res 33"},
    {"scene_band_npy", false, ".npy", "--res 45 --band 2.5"},
    {"mesh_band_pvti", true, ".pvti", "--res 44 --band 2"},
    {"scene_dense_pvti", false, ".pvti", "--res 30 26 35 --precision double"},
};

class MpiMatchesSerial : public ::testing::TestWithParam<int> {};

TEST_P(MpiMatchesSerial, BitForBit) {
  const int ranks = GetParam();
  const std::string dir = test_dir();
  const std::string mesh = torus_obj(dir);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string in = c.mesh ? mesh : scene_path();
    const bool pvti = std::string(c.ext) == ".pvti";
    const std::string ser = dir + "/" + c.name + "_serial" + (pvti ? ".vti" : c.ext);
    const std::string par = dir + "/" + c.name + "_mpi" + c.ext;
    const RunResult s = run("sdf '" + in + "' -o '" + ser + "' " + c.opts + " -q --threads 2");
    ASSERT_EQ(s.code, 0) << s.err;
    const RunResult m =
        run_mpi(ranks, "sdf '" + in + "' -o '" + par + "' " + c.opts + " --json --threads 1");
    ASSERT_EQ(m.code, 0) << m.err;
    const auto j = nlohmann::json::parse(m.out);
    EXPECT_EQ(j["mpi"]["ranks"].get<int>(), ranks);
    EXPECT_GE(j["mpi"]["imbalance_estimated"].get<double>(), 1.0);
    EXPECT_GE(j["mpi"]["imbalance_measured"].get<double>(), 1.0);
    if (!pvti) {
      EXPECT_TRUE(slurp(ser) == slurp(par)) << ser << " and " << par << " differ";
      if (std::string(c.ext) == ".raw") {
        // The sidecars differ only in the file name they point to.
        std::string a = slurp(dir + "/" + c.name + "_serial.json");
        std::string b = slurp(dir + "/" + c.name + "_mpi.json");
        a = std::regex_replace(a, std::regex("_serial\\.raw"), "X.raw");
        b = std::regex_replace(b, std::regex("_mpi\\.raw"), "X.raw");
        EXPECT_EQ(a, b);
      }
    } else {
      const Vti v = read_vti(ser);
      const int dims[3] = {v.extent[1] + 1, v.extent[3] + 1, v.extent[5] + 1};
      const std::size_t width = v.type == "Float32" ? 4 : 8;
      const std::string b = slurp(ser);
      const auto us = b.find('_', b.find("<AppendedData encoding=\"raw\">"));
      const std::string serial_bytes =
          b.substr(us + 9, std::size_t(dims[0]) * dims[1] * dims[2] * width);
      EXPECT_TRUE(reassemble(par, dims, width) == serial_bytes);
      // No temporaries are left behind.
      for (const auto& f : list_dir(dir)) EXPECT_EQ(f.find("ebgeom"), std::string::npos) << f;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Ranks, MpiMatchesSerial, ::testing::Values(1, 2, 4),
                         [](const auto& p) { return std::to_string(p.param); });

/// One `ebgeom-mpi: error:` line on stderr, whatever the rank count.
int error_lines(const std::string& err) {
  int n = 0;
  for (std::size_t p = err.find("ebgeom-mpi: error"); p != std::string::npos;
       p = err.find("ebgeom-mpi: error", p + 1))
    ++n;
  return n;
}

class MpiErrors : public ::testing::TestWithParam<int> {};

TEST_P(MpiErrors, UnreadableInputEndsEveryRankWithOneError) {
  const int ranks = GetParam();
  const std::string dir = test_dir();
  for (const std::string& in :
       {dir + "/missing.obj", dir, std::string(EBGEOM_SOURCE_DIR) + "/tests/data/io/garbage.bin"}) {
    const RunResult r = run_mpi(ranks, "sdf '" + in + "' -o '" + dir + "/x.npy' --res 16");
    EXPECT_EQ(r.code, 3) << in << "\n" << r.err; // exit_input, as the serial tool
    EXPECT_EQ(error_lines(r.err), 1) << r.err;
    EXPECT_FALSE(exists(dir + "/x.npy"));
  }
  const RunResult u = run_mpi(ranks, "sdf '" + scene_path() + "' -o '" + dir + "/x.vti'");
  EXPECT_EQ(u.code, 2) << u.err;
  EXPECT_EQ(error_lines(u.err), 1) << u.err;
  // The sparse .npz is the serial tool's.
  const RunResult z =
      run_mpi(ranks, "sdf '" + scene_path() + "' -o '" + dir + "/x.npz' --band 2 --res 16");
  EXPECT_EQ(z.code, 2) << z.err;
  EXPECT_EQ(error_lines(z.err), 1) << z.err;
  EXPECT_NE(z.err.find("written by the serial ebgeom sdf only"), std::string::npos) << z.err;
}

TEST_P(MpiErrors, UnwritableOutputEndsEveryRankWithOneError) {
  const int ranks = GetParam();
  const std::string dir = test_dir();
  for (const char* ext : {".npy", ".raw", ".pvti"}) {
    const std::string out = dir + "/no/such/dir/x" + ext;
    const RunResult r = run_mpi(ranks, "sdf '" + scene_path() + "' -o '" + out + "' --res 16");
    EXPECT_EQ(r.code, 4) << ext << "\n" << r.err; // exit_output
    EXPECT_EQ(error_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("cannot open for writing"), std::string::npos) << r.err;
  }
  EXPECT_EQ(list_dir(dir).size(), 0u);
}

TEST_P(MpiErrors, GridsWithNaNAreNeverWritten) {
  // Every value is in range, but two nested scales of 1e-15 map the points to 1e30 in the
  // sphere's frame, whose squared length overflows float inside the evaluation: the serial tool
  // refuses such a grid, and so must every rank here.
  const int ranks = GetParam();
  const std::string dir = test_dir();
  std::ofstream(dir + "/s.json") << R"({"type": "transform", "scale": 1e-15,
      "child": {"type": "sphere", "radius": 1, "scale": 1e-15}})";
  for (const char* ext : {".npy", ".pvti"}) {
    const std::string out = dir + "/x" + ext;
    const RunResult r =
        run_mpi(ranks, "sdf '" + dir + "/s.json' -o '" + out + "' --res 16 --box -1 -1 -1 1 1 1");
    EXPECT_EQ(r.code, 3) << ext << "\n" << r.err; // exit_input, as the serial tool
    EXPECT_EQ(error_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("samples are NaN or infinite"), std::string::npos) << r.err;
    EXPECT_FALSE(exists(out));
  }
  const RunResult d =
      run_mpi(ranks, "sdf '" + dir + "/s.json' -o '" + dir +
                         "/d.npy' --res 16 --box -1 -1 -1 1 1 1 --precision double");
  EXPECT_EQ(d.code, 0) << d.err;
}

/// A full disk (a 256 KiB tmpfs, root only; skipped otherwise): MPI-IO's short writes must end
/// every rank with one output error, and leave no file, for each output kind.
TEST_P(MpiErrors, FullDiskEndsEveryRankWithOneErrorAndNoFile) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const int ranks = GetParam();
  const std::string mnt = test_dir();
  if (std::system(("mount -t tmpfs -o size=256k tmpfs '" + mnt + "'").c_str()) != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here";
  struct Unmount {
    std::string dir;
    ~Unmount() { (void)std::system(("umount '" + dir + "'").c_str()); }
  } unmount{mnt};
  for (const char* ext : {".npy", ".raw", ".pvti"}) {
    // 64^3 float samples: 1 MiB, four times the space.
    const std::string out = mnt + "/x" + ext;
    const RunResult r = run_mpi(ranks, "sdf '" + scene_path() + "' -o '" + out + "' --res 64");
    EXPECT_EQ(r.code, 4) << ext << "\n" << r.err; // exit_output
    EXPECT_EQ(error_lines(r.err), 1) << ext << "\n" << r.err;
    EXPECT_EQ(list_dir(mnt).size(), 0u) << ext << ": " << list_dir(mnt)[0];
  }
}

INSTANTIATE_TEST_SUITE_P(Ranks, MpiErrors, ::testing::Values(1, 2, 4),
                         [](const auto& p) { return std::to_string(p.param); });

} // namespace
