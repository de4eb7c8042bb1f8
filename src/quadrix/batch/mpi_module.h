// The interface between Quadrix and its MPI module, quadrix-mpi.so (modules/mpi/), which carries
// the messages of a run under `mpirun` (Open MPI): the shared frame counter of `quadrix batch`,
// the bands and halos of sort-first, the Frames of sort-last, the ranks' tallies. The module is
// loaded only in a process started by an MPI launcher (batch/run.h UnderMpiLauncher;
// util/module_loader.h says why and how it is found), so a plain `quadrix render` never maps
// Open MPI's libraries. It depends on nothing of Quadrix but this header.
//
// Every function acts on MPI_COMM_WORLD. Collective ones (marked) must be called by every rank
// in the same order.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace quadrix::batch {

// Raised whenever MpiMessage, MpiCounter's use or MpiModule change, so that a module of another
// build is refused.
inline constexpr int kMpiModuleAbi = 1;

// One point-to-point message of `bytes` bytes (any size: the module sends pieces MPI's int
// counts can hold, batch/mpi_piece.h).
struct MpiMessage {
    bool send = false;  // else receive into data
    char* data = nullptr;
    std::size_t bytes = 0;
    int peer = 0;
    int tag = 0;
};

// Counters in rank 0's memory that every rank adds to without rank 0 taking part (an MPI window
// of long longs, passive target).
struct MpiCounter;

// The module's table (quadrix_mpi_module() returns it).
struct MpiModule {
    int abi = kMpiModuleAbi;
    // Initialises MPI once (unless the process already did) and finalises it at exit.
    void (*start)() = nullptr;
    int (*rank)() = nullptr;
    int (*size)() = nullptr;
    // Collective: the minimum of every rank's `value`.
    int (*allMin)(int value) = nullptr;
    // Collective: every rank's `mine`, in rank order.
    std::vector<std::string> (*allGather)(const std::string& mine) = nullptr;
    // Posts every message at once and waits for all of them.
    void (*exchange)(const MpiMessage* messages, std::size_t count) = nullptr;
    // Collective: `slots` counters, zero, on rank 0.
    MpiCounter* (*counterCreate)(int slots) = nullptr;
    // Adds add[0..count) to the counters first..first+count atomically; before[] receives their
    // values before the addition.
    void (*counterAdd)(MpiCounter* counter, int first, int count, const long long* add,
                       long long* before) = nullptr;
    // Collective: frees the counters (after every rank's last counterAdd).
    void (*counterFree)(MpiCounter* counter) = nullptr;
};

}  // namespace quadrix::batch

// Defined by modules/mpi/mpi_module.cpp: in quadrix-mpi.so, or linked into targets that link
// MPI themselves (quadrix_modules_linked).
extern "C" const quadrix::batch::MpiModule* quadrix_mpi_module();
