#pragma once
// Typed errors for everything a user of loom can get wrong: a bad description, a stale handle,
// a shader that does not compile, a graph that cannot be planned. They come back as values;
// loom never aborts the process for a user error.

#include <cassert>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace loom {

/// What kind of thing went wrong; the message says which object is at fault.
enum class ErrorCode {
    InvalidArgument,  ///< a description or parameter is malformed
    InvalidHandle,    ///< null, stale (destroyed) or foreign (other device) handle
    InvalidState,     ///< a call made at the wrong time (e.g. a draw outside a render pass)
    Unsupported,      ///< the backend or device cannot do this (format, feature)
    OutOfMemory,      ///< the GPU or a heap has no room
    ShaderCompile,    ///< GLSL did not compile; message has file and line
    ShaderLink,       ///< stages do not link / pipeline creation failed
    Io,               ///< a file could not be read or written
    Parse,            ///< malformed input file (JSON graph, glTF, PNG)
    Graph,            ///< bad frame graph: unknown port, cycle, unconnected input
    Join,             ///< texture constraints of connected ports cannot be joined
    Backend,          ///< the graphics API reported an error
    DeviceLost,       ///< the GPU device was lost
};

/// The name of an error code ("ShaderCompile").
std::string_view error_code_name(ErrorCode code);

/// An error a caller can act on: a code and a message naming the object at fault.
struct Error {
    ErrorCode code = ErrorCode::InvalidArgument;
    std::string message;
    /// What the error is about, by name, for tools that map names back to where they were
    /// written (e.g. graph files to JSON pointers): passes as "pass", ports as "pass.port".
    /// Filled where the message names them (the frame graph's planning errors); may be empty.
    std::vector<std::string> subjects{};

    /// "ShaderCompile: shaders/foo.frag:12: 'x' undeclared identifier"
    [[nodiscard]] std::string to_string() const;
};

/// An Error from a code and a message.
inline Error make_error(ErrorCode code, std::string message) { return Error{code, std::move(message)}; }

/// Either a value or an Error (a small std::expected for C++20).
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : state_(std::in_place_index<0>, std::move(value)) {}  // NOLINT(implicit)
    Result(Error error) : state_(std::in_place_index<1>, std::move(error)) {}  // NOLINT(implicit)

    /// True when the result holds a value.
    [[nodiscard]] bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    /// The value (the result must be ok()).
    T& value() & { assert(ok()); return std::get<0>(state_); }
    const T& value() const& { assert(ok()); return std::get<0>(state_); }
    T&& value() && { assert(ok()); return std::get<0>(std::move(state_)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    /// The error (the result must not be ok()).
    const Error& error() const { assert(!ok()); return std::get<1>(state_); }
    /// Moves the error out, e.g. to return it from the caller.
    Error&& take_error() { assert(!ok()); return std::get<1>(std::move(state_)); }

    /// The value, or `fallback` when there is an error.
    template <class U>
    T value_or(U&& fallback) const& { return ok() ? value() : static_cast<T>(std::forward<U>(fallback)); }

private:
    std::variant<T, Error> state_;
};

/// Success or an Error.
template <>
class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(Error error) : error_(std::move(error)) {}  // NOLINT(implicit)

    /// True on success.
    [[nodiscard]] bool ok() const { return !error_.has_value(); }
    explicit operator bool() const { return ok(); }
    /// The error (the status must not be ok()).
    const Error& error() const { assert(!ok()); return *error_; }
    /// Moves the error out, e.g. to return it from the caller.
    Error&& take_error() { assert(!ok()); return std::move(*error_); }

private:
    std::optional<Error> error_;
};

using Status = Result<void>;

}  // namespace loom

/// Returns the error of a Result/Status expression from the enclosing function.
#define LOOM_TRY(expr)                                  \
    do {                                                \
        auto&& loom_try_result_ = (expr);               \
        if (!loom_try_result_.ok())                     \
            return loom_try_result_.take_error();       \
    } while (false)
