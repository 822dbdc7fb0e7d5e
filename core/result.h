// Result<T>: the value of a set-up step that can fail for a reason the user can act on (no device,
// unreadable file, bad argument), or that reason. Failures inside the frame are bugs and throw
// (see core/gpu/check.h); failures a user can cause come back as values.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace mfx {

struct Error {
    std::string message; // one sentence naming what is wrong and, where it applies, where
};

template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(state_); }
    explicit operator bool() const { return ok(); }

    T& value() & { return std::get<T>(state_); }
    T&& value() && { return std::get<T>(std::move(state_)); }
    const T& value() const& { return std::get<T>(state_); }
    const Error& error() const { return std::get<Error>(state_); }

private:
    std::variant<T, Error> state_;
};

// Result of a step with nothing to return.
struct Ok {};
using Status = Result<Ok>;

} // namespace mfx
