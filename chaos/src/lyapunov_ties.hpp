#pragma once
// Kantz's neighbourhoods on tied data (lyapunov.hpp, max_tied_neighbours). In quantised data most
// pairs of delay vectors lie at one of a few exact distances, and a radius just above the smallest
// of them takes thousands of points at once. Each group of members at one distance from the
// reference point is then represented by `cap` of them, each standing for its share of the group.
//
// Within a group the members are ordered by their delay vector (lexicographically) and, for one
// vector, by index; the representatives are those at ranks floor(r |G| / cap), r = 0 .. cap - 1.
// The order spreads them over the group's distinct vectors in proportion to how often each occurs
// and, for one vector, evenly in time. It also lets a neighbourhood made of a few repeated vectors
// be thinned without listing it: the members of one vector are a sorted list, so a rank is found
// from the lists' lengths (IdenticalVectors, thin_classes), and both ways give the same members.

#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "chaos/norm.hpp"

namespace chaos::lyapunov_detail {

// The delay vectors X_j = (y_j, y_{j+tau}, ..., y_{j+(m-1)tau}) of the scaled series.
struct DelayVectors {
  std::span<const double> y;
  std::size_t m, tau;
  Norm norm;
  // |X_i - X_j|: the operations of the divergence curves' k = 0 distance, to the last bit.
  double distance(std::size_t i, std::size_t j) const noexcept;
  // X_a before X_b lexicographically (coordinates compared with <; equal ones, == , tie).
  bool less(std::size_t a, std::size_t b) const noexcept;
};

// The members a reference point's mean follows, in ascending index order, each with the number of
// neighbourhood members it stands for.
struct Thinned {
  std::vector<std::size_t> index;
  std::vector<double> weight;
};

// The thinned neighbourhood of reference i from its listed members (ascending), into `out`; false,
// leaving `out` as it is, when no group has more than `cap` members (cap 0: never).
bool thin_ties(const DelayVectors& v, std::size_t i, std::span<const std::size_t> members, std::size_t cap,
               std::vector<std::pair<double, std::size_t>>& scratch, Thinned& out);

// The first `points` delay vectors grouped by value, when few values hold them all (quantised
// data): classes numbered in the lexicographic order of their vectors, each class's points
// ascending. Coordinates equal under == are one value (+0 and -0 alike), so every member of a
// class is at the same distance from any point.
struct IdenticalVectors {
  std::vector<std::size_t> representative;        // per class: its first point
  std::vector<std::vector<std::size_t>> members;  // per class, ascending
};

// The classes when there are at most `max_classes` of them, else nullopt (the search stops at the
// first one too many, so untied data cost about max_classes probes).
std::optional<IdenticalVectors> identical_vectors(const DelayVectors& v, std::size_t points, std::size_t max_classes);

// Kantz's neighbourhood of reference i as whole classes: those at distance 0 < d < eps, with their
// members outside the Theiler window |i - j| <= w counted, not listed.
struct ClassNeighbourhood {
  struct Entry {
    double distance;
    std::size_t cls;
    std::size_t admissible;          // members outside the window
    std::size_t window_begin, window_end;  // the window's positions in the class's member list
  };
  std::vector<Entry> entries;  // ascending (distance, class)
  std::size_t found = 0;       // the neighbourhood's size: the sum of `admissible`
};
void class_neighbourhood(const IdenticalVectors& classes, const DelayVectors& v, std::size_t i, double eps,
                         std::size_t theiler, ClassNeighbourhood& out);

// thin_ties for a neighbourhood given as classes: the same members and weights, found from the
// lists' lengths. False, leaving `out` as it is, when no group has more than `cap` members.
bool thin_classes(const IdenticalVectors& classes, const ClassNeighbourhood& neighbourhood, std::size_t cap,
                  Thinned& out);

// The neighbourhood's members, ascending (what KdTree::within lists).
void list_members(const IdenticalVectors& classes, const ClassNeighbourhood& neighbourhood,
                  std::vector<std::size_t>& out);

}  // namespace chaos::lyapunov_detail
