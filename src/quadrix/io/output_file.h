// The one output writer of Quadrix (DESIGN.md "Reliability rules"; rules in docs/output.md).
//
// Every file Quadrix produces (images, frame dumps, text drawings, exported and generated scenes)
// is written through OutputFile:
//
//  1. Check the target (CheckOutputPath): it must not exist, or be a regular file. A directory,
//     FIFO, socket or device node is refused, never replaced. A symbolic link is written through:
//     the file it points to (after every link is followed) is the target and the link stays; a
//     dangling link is refused. The target must not be a file this process has read (an input:
//     same device and inode, see NoteInputFile) nor one of the inputs named to CheckOutputPaths.
//  2. Create the temporary file with mkstemp (O_EXCL, an unguessable name, mode 0600) in the
//     target's directory, so the rename below stays within one file system.
//  3. Write, fflush, fchmod to the mode of the existing target (else 0666 minus the umask).
//  4. Check the target again and rename the temporary file over it.
//
// Steps 1–4 make an output whole or absent whatever happens to this process. Durability across a
// power loss or a kernel crash (the file's data and the rename on the disk before the command
// ends) is asked for with QUADRIX_FSYNC=1 (OutputSync): then the file is fsynced before the
// rename and its directory after it. Off by default, as for other renderers' and image tools'
// outputs, which can be made again: the two fsyncs were 1–6 ms of every command (at 64×64 half
// of the whole process; docs/performance.md).
//
// Until the rename, the temporary file's path sits in a fixed table that the SIGINT/SIGTERM/SIGHUP
// handlers (installed with the first OutputFile, only where the signal's disposition is the
// default) unlink before re-raising the signal, so an interrupted write leaves nothing behind.
//
// A command with several outputs checks them all (CheckOutputPaths) before it writes any, or opens
// all its OutputFiles, writes them and commits them together (CommitAll), so a refused output
// leaves no partial set.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace quadrix {

// Why `path` may not be written as an output (see rule 1 above), or empty when it may. "-"
// (standard output) is always allowed.
std::string CheckOutputPath(const std::string& path);
// Checks every output, that no two of them are the same file, and that none is one of `inputs`
// (paths; "-" and files that do not exist are skipped). Empty string when all may be written.
std::string CheckOutputPaths(const std::vector<std::string>& outputs,
                             const std::vector<std::string>& inputs = {});

// True when both paths name one existing file (same device and inode, links followed).
bool IsSameFile(const std::string& a, const std::string& b);

// Records a file this process has read (its device, inode and change time), so that it is never
// replaced by an output. The bounded reader (io/bounded_read.h) calls it for every file it reads.
void NoteInputFile(int fd);

// One output file in the making; "-" is standard output (the bytes are kept in an anonymous
// temporary file and copied to stdout at Commit, so a failed write sends nothing). Not copyable;
// the destructor removes the temporary file unless Commit() succeeded.
class OutputFile {
  public:
    explicit OutputFile(const std::string& path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    // False when the target was refused or the temporary file could not be created (see error()).
    bool ok() const { return file_ != nullptr; }
    const std::string& error() const { return error_; }
    const std::string& path() const { return path_; }
    // The stream to write to (nullptr when !ok()).
    std::FILE* stream() { return file_; }
    void Write(std::string_view bytes);

    // Flushes, syncs (when OutputSync) and renames into place; empty string on success, else a
    // one-line message and the temporary file is gone.
    std::string Commit();
    // Flushes (and syncs) without renaming (the first half of Commit; CommitAll runs it on every
    // file before renaming any).
    std::string Finish();

  private:
    std::string Rename();
    std::string CopyToStdout();

    std::string path_;    // as given (messages)
    std::string target_;  // after following symbolic links
    std::string tmp_;
    std::string error_;
    std::FILE* file_ = nullptr;
    int slot_ = -1;  // in the signal handlers' table
    unsigned mode_ = 0;
    bool finished_ = false;
    bool committed_ = false;
    bool toStdout_ = false;
};

// Finishes every file, then renames them all; stops at the first failure (the files not yet
// renamed are removed). Empty string on success.
std::string CommitAll(const std::vector<OutputFile*>& files);

// Writes `contents` to `path` through an OutputFile; "-" writes to standard output. Empty string
// on success, else a one-line message (and no file is left behind).
std::string WriteOutputFile(const std::string& path, std::string_view contents);

// Whether Commit fsyncs each file and its directory (see the file comment): QUADRIX_FSYNC in the
// environment when the process first asks (OutputSyncFromEnvironment), unless SetOutputSync
// chose. OutputSyncCount: the fsyncs made so far by this process (tests).
bool OutputSync();
void SetOutputSync(bool sync);
long OutputSyncCount();
// QUADRIX_FSYNC's value: unset, empty or "0" is off; anything else is on.
bool OutputSyncFromEnvironment(const char* value);

// Unlinks every temporary output file in the making. Async-signal-safe (for a signal handler
// that ends the process, e.g. the time limit's).
void RemoveTemporaryOutputFiles();

// Number of temporary files currently registered with the signal handlers (tests).
int PendingOutputFiles();

}  // namespace quadrix
