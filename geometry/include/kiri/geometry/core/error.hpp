#pragma once
//! \file error.hpp
//! kiri's error policy: typed exceptions at API boundaries carry the file,
//! the field (a JSON pointer, a raster property or a parameter name) and the reason.
//! The CLI prints what() as one line and exits with code 2.
#include <stdexcept>
#include <string>

namespace kiri {

//! Base of every error kiri throws on purpose.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

//! Bad input: a file, a field in it and why it was refused.
//! what() reads "FILE: FIELD: REASON" (parts that are empty are left out).
class InputError : public Error {
public:
    InputError(std::string file, std::string field, std::string reason);
    const std::string& file() const noexcept { return file_; }
    const std::string& field() const noexcept { return field_; }
    const std::string& reason() const noexcept { return reason_; }

private:
    std::string file_, field_, reason_;
};

//! A request above a documented resource limit, refused before allocating.
class LimitError : public InputError {
public:
    using InputError::InputError;
};

//! Reading or writing failed for reasons outside the input's content (permissions, disk).
class IoError : public InputError {
public:
    using InputError::InputError;
};

}  // namespace kiri
