#pragma once
// Test support: the perinom program run as a user runs it, in a scratch folder. Two branches
// extracted the same helpers on one day; they live in cli.hpp, and this header names the
// ones the tests written against it use in the global namespace.
#include "cli.hpp"

namespace fs = std::filesystem;
using cli_test::Outcome;
using cli_test::perinom;
using cli_test::require_one_clear_error;
using cli_test::ScratchDir;
using cli_test::slurp;
