//! Named systems ordered by constraints, resolved once into a fixed order.

use std::fmt;

use super::error::ScheduleError;
use super::graph::topological_order;
use crate::ecs::World;

/// A system as stored by the schedule.
pub type BoxedSystem = Box<dyn FnMut(&mut World) + Send>;

struct SystemEntry {
    name: String,
    run: BoxedSystem,
    after: Vec<String>,
    before: Vec<String>,
    sets: Vec<String>,
}

struct SetEntry {
    name: String,
    after: Vec<String>,
    before: Vec<String>,
}

/// An ordered list of named systems.
///
/// Systems are ordered by `.after(label)` / `.before(label)` constraints, where
/// a label is a system name or a set name (`.in_set(name)` puts a system in a
/// set; [`Schedule::configure_set`] orders whole sets). [`Schedule::build`]
/// resolves the constraints once into a fixed order: topological, with ties
/// broken by insertion order, so the order is deterministic.
///
/// [`Schedule::run`] runs the systems in that order and applies the world's
/// deferred commands ([`World::commands`]) **after each system**, so every
/// system sees the structural changes of the systems before it.
///
/// ```
/// use engine::ecs::World;
/// use engine::schedule::Schedule;
///
/// struct Log(Vec<&'static str>);
/// let mut schedule = Schedule::new();
/// schedule.add_system("render", |w: &mut World| w.resource_mut::<Log>().0.push("render"));
/// schedule.add_system("gait", |w: &mut World| w.resource_mut::<Log>().0.push("gait")).in_set("character");
/// schedule.add_system("input", |w: &mut World| w.resource_mut::<Log>().0.push("input")).before("character");
/// schedule.configure_set("character").before("render");
/// schedule.build().unwrap();
/// assert_eq!(schedule.order(), vec!["input", "gait", "render"]);
///
/// let mut world = World::new();
/// world.insert_resource(Log(Vec::new()));
/// schedule.run(&mut world).unwrap();
/// assert_eq!(world.resource::<Log>().0, vec!["input", "gait", "render"]);
/// ```
#[derive(Default)]
pub struct Schedule {
    systems: Vec<SystemEntry>,
    sets: Vec<SetEntry>,
    /// Indices into `systems`; `None` until built or after a change.
    resolved: Option<Vec<usize>>,
}

/// Chains ordering constraints onto a just-added system.
pub struct SystemConfig<'s> {
    schedule: &'s mut Schedule,
    index: usize,
}

impl SystemConfig<'_> {
    fn entry(&mut self) -> &mut SystemEntry {
        self.schedule.resolved = None;
        &mut self.schedule.systems[self.index]
    }

    /// Runs after the system or every system of the set named `label`.
    pub fn after(mut self, label: impl Into<String>) -> Self {
        self.entry().after.push(label.into());
        self
    }

    /// Runs before the system or every system of the set named `label`.
    pub fn before(mut self, label: impl Into<String>) -> Self {
        self.entry().before.push(label.into());
        self
    }

    /// Joins set `set` (created on first mention).
    pub fn in_set(mut self, set: impl Into<String>) -> Self {
        self.entry().sets.push(set.into());
        self
    }
}

/// Chains ordering constraints onto a set.
pub struct SetConfig<'s> {
    schedule: &'s mut Schedule,
    index: usize,
}

impl SetConfig<'_> {
    fn entry(&mut self) -> &mut SetEntry {
        self.schedule.resolved = None;
        &mut self.schedule.sets[self.index]
    }

    /// Every system of this set runs after the system or set `label`.
    pub fn after(mut self, label: impl Into<String>) -> Self {
        self.entry().after.push(label.into());
        self
    }

    /// Every system of this set runs before the system or set `label`.
    pub fn before(mut self, label: impl Into<String>) -> Self {
        self.entry().before.push(label.into());
        self
    }
}

impl Schedule {
    /// An empty schedule.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a system named `name`; chain `.after(..)`, `.before(..)`, `.in_set(..)`.
    /// A name used twice is reported by [`Schedule::build`] as
    /// [`ScheduleError::DuplicateName`].
    pub fn add_system(
        &mut self,
        name: impl Into<String>,
        system: impl FnMut(&mut World) + Send + 'static,
    ) -> SystemConfig<'_> {
        self.resolved = None;
        self.systems.push(SystemEntry {
            name: name.into(),
            run: Box::new(system),
            after: Vec::new(),
            before: Vec::new(),
            sets: Vec::new(),
        });
        SystemConfig {
            index: self.systems.len() - 1,
            schedule: self,
        }
    }

    /// Orders set `name` as a whole (created if new); constraints accumulate.
    pub fn configure_set(&mut self, name: impl Into<String>) -> SetConfig<'_> {
        let name = name.into();
        let index = match self.sets.iter().position(|s| s.name == name) {
            Some(index) => index,
            None => {
                self.sets.push(SetEntry {
                    name,
                    after: Vec::new(),
                    before: Vec::new(),
                });
                self.sets.len() - 1
            }
        };
        SetConfig {
            schedule: self,
            index,
        }
    }

    /// Replaces the function of system `name`, keeping its position and constraints.
    pub fn replace(
        &mut self,
        name: &str,
        system: impl FnMut(&mut World) + Send + 'static,
    ) -> Result<(), ScheduleError> {
        let index = self.index_of(name)?;
        self.systems[index].run = Box::new(system);
        Ok(())
    }

    /// Removes system `name`. Constraints of other systems and sets that name
    /// it are dropped too (unless a set of that name remains), so orderings
    /// that went *through* it no longer hold. The order is re-resolved.
    pub fn remove(&mut self, name: &str) -> Result<(), ScheduleError> {
        let index = self.index_of(name)?;
        self.systems.remove(index);
        self.resolved = None;
        if !self.is_set(name) {
            let keep = |label: &String| label != name;
            for system in &mut self.systems {
                system.after.retain(keep);
                system.before.retain(keep);
            }
            for set in &mut self.sets {
                set.after.retain(keep);
                set.before.retain(keep);
            }
        }
        Ok(())
    }

    /// Whether a system has this name.
    pub fn contains(&self, name: &str) -> bool {
        self.systems.iter().any(|s| s.name == name)
    }

    /// Number of systems.
    pub fn len(&self) -> usize {
        self.systems.len()
    }

    /// Whether there are no systems.
    pub fn is_empty(&self) -> bool {
        self.systems.is_empty()
    }

    /// Whether the current constraints are resolved (no change since the last
    /// successful [`Schedule::build`]).
    pub fn is_built(&self) -> bool {
        self.resolved.is_some()
    }

    fn index_of(&self, name: &str) -> Result<usize, ScheduleError> {
        self.systems
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| ScheduleError::UnknownSystem(name.to_owned()))
    }

    fn is_set(&self, name: &str) -> bool {
        self.sets.iter().any(|s| s.name == name)
            || self
                .systems
                .iter()
                .any(|s| s.sets.iter().any(|x| x == name))
    }

    /// Systems denoted by `label`: the system of that name and the members of
    /// the set of that name. `None` if it is neither.
    fn resolve(&self, label: &str) -> Option<Vec<usize>> {
        let members: Vec<usize> = (0..self.systems.len())
            .filter(|&i| {
                self.systems[i].name == label || self.systems[i].sets.iter().any(|s| s == label)
            })
            .collect();
        (!members.is_empty() || self.is_set(label)).then_some(members)
    }

    /// Adds `(before, after)` edges between every pair, skipping self-pairs.
    fn constrain(
        &self,
        owner: &str,
        subjects: &[usize],
        after: &[String],
        before: &[String],
        edges: &mut Vec<(usize, usize)>,
    ) -> Result<(), ScheduleError> {
        let unknown = |label: &String| ScheduleError::UnknownLabel {
            system: owner.to_owned(),
            label: label.clone(),
        };
        for label in after {
            let others = self.resolve(label).ok_or_else(|| unknown(label))?;
            for &s in subjects {
                edges.extend(others.iter().filter(|&&o| o != s).map(|&o| (o, s)));
            }
        }
        for label in before {
            let others = self.resolve(label).ok_or_else(|| unknown(label))?;
            for &s in subjects {
                edges.extend(others.iter().filter(|&&o| o != s).map(|&o| (s, o)));
            }
        }
        Ok(())
    }

    /// Resolves the constraints into the fixed run order.
    pub fn build(&mut self) -> Result<(), ScheduleError> {
        for (i, system) in self.systems.iter().enumerate() {
            if self.systems[..i].iter().any(|s| s.name == system.name) {
                return Err(ScheduleError::DuplicateName(system.name.clone()));
            }
        }
        let mut edges = Vec::new();
        for (i, system) in self.systems.iter().enumerate() {
            self.constrain(
                &system.name,
                &[i],
                &system.after,
                &system.before,
                &mut edges,
            )?;
        }
        for set in &self.sets {
            let members = self.resolve(&set.name).unwrap_or_default();
            let owner = format!("set {}", set.name);
            self.constrain(&owner, &members, &set.after, &set.before, &mut edges)?;
        }
        let order = topological_order(self.systems.len(), &edges).map_err(|cycle| {
            ScheduleError::Cycle {
                systems: cycle
                    .iter()
                    .map(|&i| self.systems[i].name.clone())
                    .collect(),
            }
        })?;
        self.resolved = Some(order);
        Ok(())
    }

    /// The resolved order of system names; before the first successful
    /// [`Schedule::build`] (or after a change), the insertion order.
    pub fn order(&self) -> Vec<&str> {
        match &self.resolved {
            Some(order) => order
                .iter()
                .map(|&i| self.systems[i].name.as_str())
                .collect(),
            None => self.systems.iter().map(|s| s.name.as_str()).collect(),
        }
    }

    /// Prints the order to standard output, one numbered system per line.
    pub fn print_order(&self) {
        print!("{self}");
    }

    /// Runs every system once in the resolved order (building first if
    /// needed), applying the world's deferred commands after each system.
    /// Stops at the first system whose commands fail.
    pub fn run(&mut self, world: &mut World) -> Result<(), ScheduleError> {
        if self.resolved.is_none() {
            self.build()?;
        }
        let order = self.resolved.as_ref().expect("built above");
        for &index in order {
            let system = &mut self.systems[index];
            (system.run)(world);
            world
                .apply_commands()
                .map_err(|source| ScheduleError::Commands {
                    system: system.name.clone(),
                    source,
                })?;
        }
        Ok(())
    }
}

impl fmt::Display for Schedule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.is_built() {
            writeln!(f, "(not built: insertion order)")?;
        }
        for (i, name) in self.order().iter().enumerate() {
            writeln!(f, "{:>3}. {name}", i + 1)?;
        }
        Ok(())
    }
}

impl fmt::Debug for Schedule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Schedule")
            .field("order", &self.order())
            .field("built", &self.is_built())
            .finish()
    }
}
