// The one routine that writes an output file, for every tool and every
// output (-o, -i, --trajectory, --diff-output, render baselines).  What it
// does depends on what is at the path (README "Outputs", the man pages'
// FILES section):
//
// - nothing: a new file, created through a temporary file + rename, with
//   mode 0666 less the umask (and the directory's default ACL).
// - a regular file: replaced atomically by a temporary file in its own
//   directory + rename(2); mode kept, owner and group kept where the process
//   may set them (root; a user for the groups they are in).
// - a symbolic link (chain): the link stays; its final target is replaced as
//   above, in the target's directory.  A dangling link is refused (like
//   cp(1)): writing through it would create a file wherever it points.
// - a character device or FIFO (/dev/null, a terminal, a pipe): opened for
//   writing and written through, never truncated or replaced.  A FIFO with
//   no reader waits for one, as a shell redirection does.
// - /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: written to that
//   open descriptor, whatever it is (like gawk and bash).
// - refused, nothing changed: a regular file with no write permission bit at
//   all (even for root: a read-only file is a statement of intent) or that
//   the process may not write; a regular file with more than one hard link
//   (replacing it would silently split the links, writing in place would
//   change the other names too and is not atomic); a directory, block
//   device or socket.
//
// Interrupted writes: the temporary file is registered in temp_files.hpp
// from before it exists until after the rename, so a signal handler can
// remove it.  On any failure the temporary file is removed and the path is
// left as it was.
#pragma once
#include <functional>
#include <string>

#include "core/writer.hpp"

namespace rscene {

// Writes produce()'s output to `path`.  produce() returning false cancels
// the write (nothing at `path` changes, except that a device or FIFO may
// already have received part of it).  On failure `error` gets a lower-case
// message without the path ("permission denied"; "has 2 hard links ...").
bool writeOutputFile(const std::string& path, const std::function<bool(Sink&)>& produce, std::string* error);

// Whether writeOutputFile() would refuse `path` before producing anything
// (read-only, hard-linked, a dangling link, a directory, an unwritable
// directory for a new file ...), with the same message; writes nothing.
// Tools with several outputs check them all first, so that one refused
// output does not leave the others already replaced.
bool checkOutputFile(const std::string& path, std::string* error);

// Whether two output paths end at the same file (through links, ./ and
// ../, or /dev/stdout and a file on descriptor 1).  Character devices
// (/dev/null, a terminal) never count: writing both there loses nothing.
bool sameOutputFile(const std::string& a, const std::string& b);

}  // namespace rscene
