//! Properties that vary along the line, element by element (line sections
//! and buoyancy modules, docs/theory.md §11): [`PerElement`] holds the few
//! distinct values of a line and, per element, which one is its own, so a
//! uniform line stores one value and every element reads it.

use crate::loads::fluid::Fluid;
use crate::loads::morison::DragCoefficients;
use crate::loads::seabed::Seabed;
use crate::loads::surface::FreeSurface;
use crate::loads::{self};
use crate::scene::Scene;
use crate::scene::sections::{LineProperties, per_element};

/// One value per element, stored once per distinct value.
#[derive(Debug, Clone)]
pub struct PerElement<T> {
    values: Vec<T>,
    of: Vec<u32>,
}

impl<T> PerElement<T> {
    /// The same value on `n_el` elements.
    pub fn uniform(value: T, n_el: usize) -> Self {
        PerElement { values: vec![value], of: vec![0; n_el] }
    }

    /// The value of element e.
    #[inline]
    pub fn at(&self, e: usize) -> &T {
        // (a uniform line, the common case, reads its one value without the index)
        if self.values.len() == 1 { &self.values[0] } else { &self.values[self.of[e] as usize] }
    }

    /// The distinct values (the first is element 0's).
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// The first element's value (every element's on a uniform line).
    pub fn first(&self) -> &T {
        &self.values[0]
    }

    /// Number of elements.
    pub fn n_el(&self) -> usize {
        self.of.len()
    }

    /// The same layout with every value mapped.
    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> PerElement<U> {
        PerElement { values: self.values.iter().map(f).collect(), of: self.of.clone() }
    }
}

impl<T: PartialEq> PerElement<T> {
    /// From one value per element (equal values stored once).
    pub fn from_elements(per_element: Vec<T>) -> Self {
        let mut values: Vec<T> = Vec::new();
        let mut of = Vec::with_capacity(per_element.len());
        for v in per_element {
            let i = match values.iter().position(|u| *u == v) {
                Some(i) => i,
                None => {
                    values.push(v);
                    values.len() - 1
                }
            };
            of.push(i as u32);
        }
        PerElement { values, of }
    }
}

/// The properties of each element of a scene's line (its sections and
/// modules averaged over the elements, [`crate::scene::sections::element_properties`]).
pub fn element_properties(scene: &Scene) -> PerElement<LineProperties> {
    PerElement::from_elements(per_element(&scene.pieces(), scene.line.length, scene.analysis.n_elements))
}

/// Drag, added mass and free surface of each element.
pub fn fluid(scene: &Scene, props: &PerElement<LineProperties>) -> PerElement<Fluid> {
    props.map(|p| loads::fluid_of(scene, p))
}

/// The seabed under each element (its contact width), None without a seabed.
pub fn seabed(scene: &Scene, props: &PerElement<LineProperties>) -> Option<PerElement<Seabed>> {
    scene.seabed.as_ref()?;
    Some(props.map(|p| loads::seabed_of(scene, p).expect("the scene has a seabed")))
}

/// The free surface as each element feels it.
pub fn free_surface(scene: &Scene, props: &PerElement<LineProperties>) -> PerElement<FreeSurface> {
    props.map(|p| loads::free_surface_of(scene, p))
}

/// Morison drag coefficients of each element.
pub fn drag_coefficients(scene: &Scene, props: &PerElement<LineProperties>) -> PerElement<DragCoefficients> {
    props.map(|p| loads::drag_coefficients_of(scene, p))
}

/// The water on a line of sections.
impl PerElement<Fluid> {
    /// True if the water exerts no force on any element beyond weight and buoyancy.
    pub fn is_inert(&self) -> bool {
        self.values().iter().all(Fluid::is_inert)
    }

    /// The same in waves (`waves`) or in still water.
    pub fn is_inert_in(&self, waves: bool) -> bool {
        self.values().iter().all(|f| f.is_inert_in(waves))
    }

    /// The largest added mass per length, kg/m.
    pub fn max_added_mass(&self) -> f64 {
        self.values().iter().map(|f| f.added_mass).fold(0.0, f64::max)
    }
}

/// The seabed's geometry is the same under every element; only the contact
/// width (the stiffness and damping per length) varies.
impl PerElement<Seabed> {
    /// Penetration of a point (> 0 below the plane), m.
    pub fn penetration(&self, x: &crate::math::V3) -> f64 {
        self.first().penetration(x)
    }

    /// Height of the seabed under (x, y), m.
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        self.first().height_at(x, y)
    }

    /// The largest round-off of an element's contact force, N.
    pub fn roundoff(&self, len: f64, extent: f64) -> f64 {
        self.values().iter().map(|b| b.roundoff(len, extent)).fold(0.0, f64::max)
    }
}
