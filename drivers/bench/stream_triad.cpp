// stream_triad: the memory bandwidth this machine gives the dual operator,
// measured the way STREAM's triad does (a = b + s c over arrays far larger
// than the caches), on every MPI rank at once, so that the ranks compete for
// memory as the FETI ranks do. It also times the kernel the explicit dual
// operator runs, the packed symmetric product over blocks of the size given,
// which reads each stored value once: its bandwidth is the bound of one
// application of F. Three variants: double blocks (dspmv), float blocks
// summed in float (sspmv), and float blocks summed in double
// (Blas::spmvMixed, what Dense Block Precision = Single runs).
//
//   mpirun -np R tribos_stream_triad [--mb MB] [--block n] [--repeat k]
//
// Prints one line per kernel: bytes moved per rank, the best time over the
// repetitions, and the bandwidth summed over the ranks (GB/s = 1e9 bytes/s).
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Tribos_DenseBlas.hpp"
#include "Tribos_ProcessStartup.hpp"

namespace {

struct Options {
  double mb = 800;   // per rank, over the three triad arrays / the packed blocks
  int block = 654;   // rows of one packed block (an interior subdomain of 6^3 Tet4 cells)
  int repeat = 10;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw std::runtime_error("option " + a + " needs a value");
    char* end = nullptr;
    const double v = std::strtod(argv[++i], &end);
    if (*end != '\0' || !(v > 0)) throw std::runtime_error("option " + a + ": not a positive number: " + argv[i]);
    if (a == "--mb") o.mb = v;
    else if (a == "--block") o.block = static_cast<int>(v);
    else if (a == "--repeat") o.repeat = static_cast<int>(v);
    else throw std::runtime_error("unknown option " + a + " (valid: --mb, --block, --repeat)");
  }
  return o;
}

// Best wall time of `kernel` over `repeat` runs, every rank starting together;
// the slowest rank's time counts (the bandwidth is what all ranks get at once).
template <class Kernel>
double bestTime(int repeat, Kernel kernel) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto t0 = std::chrono::steady_clock::now();
    kernel();
    double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    best = std::min(best, t);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  Tribos::prepareProcess();  // before MPI_Init and any BLAS call
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int status = 0;
  try {
    const Options o = parse(argc, argv);
    // Triad: a = b + s c; 24 bytes per index (two reads, one write; the
    // write-allocate read that some caches add is not counted, as in STREAM).
    const size_t n = static_cast<size_t>(o.mb * 1048576.0 / 24.0);
    std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
    const double s = 3.0;
    const double triad = bestTime(o.repeat, [&] {
      for (size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    });
    // Packed symmetric products over as many blocks as fill the same memory.
    const size_t packed = static_cast<size_t>(o.block) * (o.block + 1) / 2;
    const size_t blocks = std::max<size_t>(1, static_cast<size_t>(o.mb * 1048576.0 / 8.0 / packed));
    std::vector<double> A(packed * blocks, 1e-3), x(o.block, 1.0), y(o.block, 0.0);
    std::vector<float> Af(A.begin(), A.end()), xf(x.begin(), x.end()), yf(o.block, 0.0f);
    const double spmv = bestTime(o.repeat, [&] {
      for (size_t k = 0; k < blocks; ++k) Tribos::Blas::spmv(o.block, 1.0, A.data() + k * packed, x.data(), 0.0, y.data());
    });
    const double sspmv = bestTime(o.repeat, [&] {
      for (size_t k = 0; k < blocks; ++k)
        Tribos::Blas::spmv(o.block, 1.0f, Af.data() + k * packed, xf.data(), 0.0f, yf.data());
    });
    const double mixed = bestTime(o.repeat, [&] {
      for (size_t k = 0; k < blocks; ++k) Tribos::Blas::spmvMixed(o.block, Af.data() + k * packed, x.data(), y.data());
    });
    if (rank == 0) {
      const double triadBytes = 24.0 * n, spmvBytes = 8.0 * packed * blocks;
      std::printf("ranks %d\n", size);
      std::printf("triad        %8.1f MB per rank  %8.4f s  %7.2f GB/s\n", triadBytes / 1048576.0, triad,
                  size * triadBytes / triad / 1e9);
      std::printf("dspmv n=%-5d %8.1f MB per rank  %8.4f s  %7.2f GB/s\n", o.block, spmvBytes / 1048576.0, spmv,
                  size * spmvBytes / spmv / 1e9);
      std::printf("sspmv n=%-5d %8.1f MB per rank  %8.4f s  %7.2f GB/s\n", o.block, spmvBytes / 2 / 1048576.0, sspmv,
                  size * spmvBytes / 2 / sspmv / 1e9);
      std::printf("mixed n=%-5d %8.1f MB per rank  %8.4f s  %7.2f GB/s\n", o.block, spmvBytes / 2 / 1048576.0, mixed,
                  size * spmvBytes / 2 / mixed / 1e9);
    }
  } catch (const std::exception& e) {
    if (rank == 0) std::fprintf(stderr, "tribos_stream_triad: %s\n", e.what());
    status = 1;
  }
  MPI_Finalize();
  return status;
}
