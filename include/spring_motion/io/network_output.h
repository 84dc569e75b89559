// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_IO_NETWORK_OUTPUT_H
#define SPRING_MOTION_IO_NETWORK_OUTPUT_H

#include <spring_motion/Error.h>
#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/skewness.h>
#include <spring_motion/validity.h>

#include <iterator>
#include <utility>
#include <vector>

namespace spring_motion {

/// The network's mesh at positions x, as an Indexed_mesh for the writers;
/// its boundary facets (found from the elements) carry label 0.
template <int D>
Indexed_mesh<D> make_indexed_mesh(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x)
{
  Indexed_mesh<D> m;
  m.points = x;
  m.elements = net.elements;
  m.element_labels.assign(net.number_of_elements(), 0);
  m.boundary_facets = net.boundary_facets;
  m.boundary_labels.assign(net.boundary_facets.size(), 0);
  return m;
}

/// The per-point and per-cell arrays written with a deformed mesh:
/// "displacement" (3 components, from the initial points), "skewness" (R of
/// Eq. 13) and "valid" (1 when the element keeps its recorded orientation).
/// `skewness`: R of each element at x when the caller has it already (a
/// run's Deform_report::element_skewness at its final state), else null.
template <int D>
void motion_data_arrays(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                        const Orientation_record& record, std::vector<Data_array>& point_data,
                        std::vector<Data_array>& cell_data, const std::vector<double>* skewness = nullptr)
{
  SPRING_MOTION_CHECK(!skewness || skewness->size() == net.number_of_elements(),
                      "motion_data_arrays: " << skewness->size() << " skewness values for "
                                             << net.number_of_elements() << " elements");
  Data_array disp{"displacement", 3, std::vector<double>(3 * x.size(), 0.0)};
  for(std::size_t i = 0; i < x.size(); ++i)
    for(int c = 0; c < D; ++c)
      disp.values[3 * i + c] = x[i][c] - net.points[i][c];
  Data_array r{"skewness", 1, skewness ? *skewness : element_skewness(net, x)};
  Data_array valid{"valid", 1, std::vector<double>(net.number_of_elements(), 1.0)};
  std::vector<std::size_t> bad;
  find_inverted_elements(net, x, record, std::back_inserter(bad));
  for(std::size_t t : bad)
    valid.values[t] = 0.0;
  // moved, not copied (an initializer list would copy each array)
  point_data.clear();
  point_data.push_back(std::move(disp));
  cell_data.clear();
  cell_data.push_back(std::move(r));
  cell_data.push_back(std::move(valid));
}

} // namespace spring_motion

#endif
