#pragma once
#include <cstddef>
#include <string_view>

namespace gearpatch {

/// The row of an enum's one table (rows with `key` and `name`) whose key is
/// `key`; every value of the enum has a row.
template <class Row, std::size_t N>
constexpr const Row& row_of(const Row (&table)[N], decltype(Row::key) key) {
  for (const Row& r : table)
    if (r.key == key) return r;
  return table[0];  // not reached: every value has a row
}

/// The row whose name is `name`, or none.
template <class Row, std::size_t N>
constexpr const Row* row_named(const Row (&table)[N], std::string_view name) {
  for (const Row& r : table)
    if (name == r.name) return &r;
  return nullptr;
}

}  // namespace gearpatch
