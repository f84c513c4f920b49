// Message latency and bandwidth between ranks 0 and 1 of an MPI job, for
// bench/mpi_simulate.py: `mpirun -np 2 build/bin/quiver_mpi_pingpong`
// prints one JSON line: latency_us (half the round trip of an 8-byte
// message) and, per message size (a 16x16 tile of RGB floats is 3 KiB),
// bandwidth_mb_s (bytes over half the round trip), medians of the repeats.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace {

// Half the median round trip of `bytes`, in seconds.
double half_round_trip(int rank, int bytes, int repeats) {
  std::vector<char> buffer(std::size_t(std::max(bytes, 1)));
  std::vector<double> times;
  for (int i = 0; i < repeats + 10; ++i) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    if (rank == 0) {
      MPI_Send(buffer.data(), bytes, MPI_BYTE, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(buffer.data(), bytes, MPI_BYTE, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (rank == 1) {
      MPI_Recv(buffer.data(), bytes, MPI_BYTE, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(buffer.data(), bytes, MPI_BYTE, 0, 0, MPI_COMM_WORLD);
    }
    if (i >= 10) times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2] / 2.0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2) {
    if (rank == 0) std::fprintf(stderr, "quiver_mpi_pingpong: run it on 2 ranks (mpirun -np 2)\n");
    MPI_Finalize();
    return 2;
  }
  const double latency = half_round_trip(rank, 8, 2000);
  const int sizes[] = {3072, 12288, 65536, 1 << 20};
  double bandwidth[4];
  for (int k = 0; k < 4; ++k) bandwidth[k] = sizes[k] / half_round_trip(rank, sizes[k], sizes[k] > 65536 ? 100 : 1000);
  if (rank == 0) {
    std::printf("{\"latency_us\": %.3f, \"bandwidth_mb_s\": {", latency * 1e6);
    for (int k = 0; k < 4; ++k) std::printf("%s\"%d\": %.1f", k ? ", " : "", sizes[k], bandwidth[k] / 1e6);
    std::printf("}}\n");
  }
  MPI_Finalize();
  return 0;
}
