#include "quadrix/batch/mpi.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "quadrix/util/module_loader.h"

// Null unless the module's source is linked into this target (quadrix_modules_linked); the
// program loads quadrix-mpi.so instead (util/module_loader.h).
#pragma weak quadrix_mpi_module

namespace quadrix::batch {

namespace {

[[noreturn]] void Fail(const std::string& why) {
    std::fprintf(stderr, "quadrix: error: started by an MPI launcher, but %s\n", why.c_str());
    std::fflush(stderr);
    std::_Exit(2);
}

const MpiModule& Load() {
    const MpiModule* m = nullptr;
    if (quadrix_mpi_module) {
        m = quadrix_mpi_module();
    } else {
        std::string error;
        const auto entry = reinterpret_cast<const MpiModule* (*)()>(
            LoadModuleSymbol("quadrix-mpi.so", "quadrix_mpi_module", &error));
        if (!entry) Fail("the MPI module cannot be loaded: " + error);
        m = entry();
    }
    if (m->abi != kMpiModuleAbi)
        Fail("quadrix-mpi.so is from another build of Quadrix (interface " +
             std::to_string(m->abi) + ", this program's " + std::to_string(kMpiModuleAbi) + ")");
    m->start();
    return *m;
}

}  // namespace

bool UnderMpiLauncher() {
#ifdef QUADRIX_HAVE_MPI
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
        if (std::getenv(v)) return true;
#endif
    return false;
}

const MpiModule& Mpi() {
    static const MpiModule& m = Load();
    return m;
}

int MpiRank() { return UnderMpiLauncher() ? Mpi().rank() : 0; }

int MpiSize() { return UnderMpiLauncher() ? Mpi().size() : 1; }

}  // namespace quadrix::batch
