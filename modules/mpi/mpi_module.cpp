// quadrix-mpi.so: the MPI calls of a distributed run (src/quadrix/batch/mpi_module.h).
#include "quadrix/batch/mpi_module.h"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>

#include "quadrix/batch/mpi_piece.h"

struct quadrix::batch::MpiCounter {
    MPI_Win win;
    long long* base = nullptr;
};

namespace quadrix::batch {

namespace {

void Start() {
    static bool started = false;
    if (started) return;
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
        MPI_Init(nullptr, nullptr);
        std::atexit([] {
            int finalised = 0;
            MPI_Finalized(&finalised);
            if (!finalised) MPI_Finalize();
        });
    }
    started = true;
}

int Rank() {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int Size() {
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

int AllMin(int value) {
    int all = 0;
    MPI_Allreduce(&value, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all;
}

// An allgather of the lengths, then of the bytes.
std::vector<std::string> AllGather(const std::string& mine) {
    const int size = Size();
    int length = static_cast<int>(mine.size());
    std::vector<int> lengths(static_cast<std::size_t>(size)), offsets(lengths.size());
    MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int total = 0;
    for (std::size_t r = 0; r < lengths.size(); ++r) {
        offsets[r] = total;
        total += lengths[r];
    }
    std::string all(static_cast<std::size_t>(total), '\0');
    MPI_Allgatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                   MPI_CHAR, MPI_COMM_WORLD);
    std::vector<std::string> each;
    for (std::size_t r = 0; r < lengths.size(); ++r)
        each.push_back(
            all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(lengths[r])));
    return each;
}

void Exchange(const MpiMessage* messages, std::size_t count) {
    std::vector<MPI_Request> requests;
    for (std::size_t i = 0; i < count; ++i) {
        const MpiMessage& m = messages[i];
        for (std::size_t at = 0; at < m.bytes; at += kMpiPiece) {
            const int n = static_cast<int>(std::min(kMpiPiece, m.bytes - at));
            MPI_Request r;
            if (m.send)
                MPI_Isend(m.data + at, n, MPI_BYTE, m.peer, m.tag, MPI_COMM_WORLD, &r);
            else
                MPI_Irecv(m.data + at, n, MPI_BYTE, m.peer, m.tag, MPI_COMM_WORLD, &r);
            requests.push_back(r);
        }
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

MpiCounter* CounterCreate(int slots) {
    auto* c = new MpiCounter;
    const bool root = Rank() == 0;
    MPI_Win_allocate(root ? static_cast<MPI_Aint>(slots) * sizeof(long long) : 0, sizeof(long long),
                     MPI_INFO_NULL, MPI_COMM_WORLD, &c->base, &c->win);
    if (root) std::fill_n(c->base, slots, 0LL);
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Win_lock_all(0, c->win);
    return c;
}

void CounterAdd(MpiCounter* c, int first, int count, const long long* add, long long* before) {
    if (count == 1)
        MPI_Fetch_and_op(add, before, MPI_LONG_LONG, 0, first, MPI_SUM, c->win);
    else
        MPI_Get_accumulate(add, count, MPI_LONG_LONG, before, count, MPI_LONG_LONG, 0, first, count,
                           MPI_LONG_LONG, MPI_SUM, c->win);
    MPI_Win_flush(0, c->win);
}

void CounterFree(MpiCounter* c) {
    MPI_Win_unlock_all(c->win);
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Win_free(&c->win);
    delete c;
}

}  // namespace

}  // namespace quadrix::batch

extern "C" __attribute__((visibility("default"))) const quadrix::batch::MpiModule*
quadrix_mpi_module() {
    using namespace quadrix::batch;
    static const MpiModule table{kMpiModuleAbi, &Start,      &Rank,     &Size,
                                 &AllMin,       &AllGather,  &Exchange, &CounterCreate,
                                 &CounterAdd,   &CounterFree};
    return &table;
}
