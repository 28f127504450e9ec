#pragma once
// Output files that appear whole, and together, or not at all.
//
// Every writer of plantarch (writeOBJ, writePLY, writeGLTF, writeUSDA, writePNG, the point
// cloud, plant structure and species writers) writes into a temporary file in the target's
// folder and puts it in place only once it is complete. On Linux that temporary has no name
// until then (O_TMPFILE), so a process killed mid-write, even by SIGKILL, leaves nothing
// behind. Where the filesystem offers no unnamed files, the temporary is named
// `<target>.tmp-<pid>-<n>`; removeTemporaryFilesOnSignal() makes SIGINT and SIGTERM remove it.
//
// An OutputSet groups the files of one job. While one is open, a finished file is held back
// instead of put in place; OutputSet::commit() puts them all in place together. A set
// destroyed without commit() (an error on the way) discards them: none of its targets is
// created or replaced. For example
//
//     plantarch::checkOutputPath("out/plant.obj");  // before any work
//     plantarch::OutputSet outputs;
//     plantarch::writeOBJ(context, "out/plant.obj");   // held back (with out/plant.mtl)
//     plantarch::writePNG(image, "out/plant.png");     // held back
//     outputs.commit();                                 // all three appear now

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace plantarch {

/// Checks, before any work, that a file can be written at `path`: the name is not empty, is
/// not a directory, and its folder exists and accepts new files (tried by creating a file
/// there, which leaves nothing). Throws plantarch::Error naming the path and why, e.g.
///   out/d.obj: cannot write: is a directory, not a file
///   /proc/x.obj: cannot write in folder /proc: Operation not permitted
void checkOutputPath(const std::string& path);

/// Holds back the files written while it is open and puts them in place together. One set
/// may be open at a time in a process; files written by any thread go to it.
class OutputSet {
public:
    /// Opens the set. Throws plantarch::Error when another set is open.
    OutputSet();
    /// Discards every file held back and not committed.
    ~OutputSet();
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    /// Puts every file held back in place, in the order they were written, and closes the
    /// set (files written afterwards go in place at once). First every file gets its
    /// temporary name and every target is checked (not a directory); a failure there throws
    /// plantarch::Error naming the file and replaces nothing. A rename that fails after
    /// that (the folder vanished meanwhile) throws too, leaving the files before it in place.
    void commit();
    /// Files held back so far.
    std::size_t size() const;

private:
    struct Held;
    std::unique_ptr<Held> held_;
};

/// Writes `bytes` to `path` as one file, whole or not at all (held back by an open set).
void writeFileAtomically(const std::string& path, std::string_view bytes);

/// Makes SIGINT and SIGTERM remove the named temporary files being written before the
/// signal ends the process (its default action). For programs, such as the plantarch
/// command, that do not handle these signals themselves.
void removeTemporaryFilesOnSignal();

/// A folder made for a job's outputs, which the job removes again when it fails. Until
/// keep(), the handler of removeTemporaryFilesOnSignal() removes it too, after the
/// temporaries in it, if it is empty by then; folders are removed in the reverse order of
/// their marks, so mark a parent before the folders made inside it.
class FolderMadeForOutputs {
public:
    explicit FolderMadeForOutputs(std::string path);
    /// Forgets the mark (the folder stays as it is; remove() has not run).
    ~FolderMadeForOutputs();
    FolderMadeForOutputs(FolderMadeForOutputs&& other) noexcept;
    FolderMadeForOutputs& operator=(FolderMadeForOutputs&&) = delete;
    FolderMadeForOutputs(const FolderMadeForOutputs&) = delete;
    FolderMadeForOutputs& operator=(const FolderMadeForOutputs&) = delete;
    /// Removes the folder if it is empty and forgets it.
    void remove();
    /// Forgets it: the folder stays, whatever happens.
    void keep();
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
    int slot_ = -1;  // -1 also when every signal slot was taken
    bool active_ = true;
};

/// Makes the folders of `folder` that do not exist yet, outermost first, each marked as a
/// FolderMadeForOutputs (outermost first in the result), so that a job that fails removes
/// them again (remove() in reverse order) and one that succeeds keeps them (keep()). Throws
/// plantarch::Error naming the folder it cannot make, after removing those it made.
std::vector<FolderMadeForOutputs> makeFoldersForOutputs(const std::string& folder);

}  // namespace plantarch
