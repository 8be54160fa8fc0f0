/// \file file_kind.hpp
/// \brief The rules by which every file beside an output (a cube's lock, journal,
/// `.partial` and ranks' parts `<cube>.part-<rank>`, an output's temporary) and every file read
/// is opened:
///
/// - a file read is a regular file, opened without blocking (O_NONBLOCK: a FIFO, which would
///   wait for a writer for ever, is refused at once by its type);
/// - a file beside an output is never followed: it is created exclusively
///   (O_CREAT | O_EXCL | O_NOFOLLOW), or, where one of a killed run is reused, opened with
///   O_NOFOLLOW and accepted only when it is a regular file with one name (a hard link to a
///   study file is not a journal); anything else there (a symbolic link, a FIFO, a folder) is
///   refused with one line naming it, never removed or written through;
/// - a temporary is removed when the process is stopped by SIGTERM, SIGINT or SIGHUP
///   (remove_temporaries_on_signals), as when it is abandoned.
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <string>

namespace pcrf::io {

/// What a cube's files beside it are called in messages ("pcrf makes its WHAT itself"): the
/// writer's own files, each refused when anything but a regular file of one name is there.
inline constexpr const char* kJournalWhat = "journal";
inline constexpr const char* kPartialWhat = "partial cube (a fold's temporary)";
/// `<cube>.part-<rank>` (cube_part.hpp): a worker rank's sealed chunks, made by that rank.
inline constexpr const char* kPartWhat = "part (a rank's sealed chunks)";

/// "a symbolic link", "a FIFO", "a folder", "a device", "a socket", "a regular file".
std::string kind_of(mode_t mode);

/// Opens `file` to read (O_RDONLY | O_NONBLOCK, then blocking again): a regular file only,
/// following a symbolic link unless `follow` is false. Returns the descriptor, or -1 with
/// errno ENOENT when `file` is not there and `missing_ok`.
/// \throws OutputError "FILE: is a FIFO, not a regular file" and the like, or naming the
/// reason it cannot be opened.
int open_regular_to_read(const std::filesystem::path& file, bool follow = true, bool missing_ok = false);

/// Creates `file` exclusively, O_CREAT | O_EXCL | O_NOFOLLOW, mode 0666 (the umask decides),
/// open for `access` (O_WRONLY or O_RDWR). -1 with errno set when it cannot (EEXIST when
/// anything, a dangling link included, is there).
int create_exclusive(const std::filesystem::path& file, int access);

/// Opens an existing file beside an output that a killed run left (a lock, a journal), for
/// `access`, without following it: accepted only when it is a regular file with one name.
/// Returns -1 (errno ENOENT) when nothing is there.
/// \throws OutputError naming it and what it is instead ("is a symbolic link; pcrf makes
/// its `what` itself: remove it").
int open_sidecar(const std::filesystem::path& file, int access, const std::string& what);

/// Checks what is at `file`, a path beside an output: nothing, or a regular file of one
/// name (a killed run's, which the caller may replace). \throws OutputError as open_sidecar.
void check_sidecar(const std::filesystem::path& file, const std::string& what);

/// Removes a regular file a killed run left at `file` (after check_sidecar), so that it can
/// be created exclusively. \throws OutputError as open_sidecar.
void remove_stale_sidecar(const std::filesystem::path& file, const std::string& what);

/// Remembers a temporary (its path), which the handler of remove_temporaries_on_signals()
/// removes. Returns a slot for forget_temporary(), or -1 when every slot is taken (then the
/// temporary is only removed as abandoned). Async-signal-safe to read, not to call.
int remember_temporary(const std::filesystem::path& file);
/// Forgets the temporary of `slot` (committed or removed). -1: nothing.
void forget_temporary(int slot);

/// Installs handlers for SIGTERM, SIGINT and SIGHUP that remove every remembered temporary,
/// then end the process by the signal's default action (so its exit status says which).
/// For commands that do not handle these signals themselves (a study stops in order instead,
/// and calls remove_temporaries() when a second signal ends it).
void remove_temporaries_on_signals();
/// Removes every remembered temporary (async-signal-safe: unlink only).
void remove_temporaries();

}  // namespace pcrf::io
