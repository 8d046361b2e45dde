// An enum's names as the scene spells them, in one table per enum, looked up both ways: the
// loader parses with the table, and summaries and the scene writer print with it, so a name is
// written once (kElasticLawNames, kContactLawNames, kContactFactorByNames).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace asperity {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<E, std::string_view>, N>;

// The value's name; "?" for a value the table lacks (never for a table that covers its enum).
template <class E, std::size_t N>
std::string name_in(const NameTable<E, N>& table, E value) {
  for (const auto& [v, name] : table) {
    if (v == value) return std::string(name);
  }
  return "?";
}

// The value a name stands for; none for an unknown name (the caller says what was expected).
template <class E, std::size_t N>
std::optional<E> value_named(const NameTable<E, N>& table, std::string_view name) {
  for (const auto& [v, n] : table) {
    if (n == name) return v;
  }
  return std::nullopt;
}

// Every name in the table's order (the candidates of a "did you mean").
template <class E, std::size_t N>
std::vector<std::string_view> names_in(const NameTable<E, N>& table) {
  std::vector<std::string_view> names;
  for (const auto& [v, name] : table) names.push_back(name);
  return names;
}

}  // namespace asperity
