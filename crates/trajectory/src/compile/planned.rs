//! Compiling a planned motion: [`PathTiming`] completes the compile options with its feed
//! reserve and compiles itself at the rate it was planned for.

use strak_curves::ParamCurveDeriv;

use super::{CompileOptions, compile, compile_into};
use crate::error::Error;
use crate::num::Number;
use crate::path::Path;
use crate::plan::{PathTiming, Timing};

impl<C: ParamCurveDeriv, const N: usize, const Z: usize> PathTiming<'_, C, N, Z> {
    /// `options` completed with what the plan reserved for feed changes when they give no
    /// limits: for a motion from [`plan`](PathTiming::plan) or [`scurve`](Self::scurve), the
    /// machine's [`Limits`](crate::Limits) (path acceleration and jerk, per-axis
    /// accelerations) and the feed share of its [`PlanOptions`](crate::PlanOptions), so that
    /// feed override, hold and resume ramp within the share the plan left free (see
    /// [`CompileOptions`]). What [`compile`](crate::compile()) uses for this plan; options
    /// with limits, and the laws without [`Limits`](crate::Limits), are returned unchanged.
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{CompileOptions, Limits, PathTiming};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?;
    /// let limits = Limits::<2>::new(100.0, 1_000.0, 20_000.0)?
    ///     .with_axis_acceleration([800.0, f64::INFINITY])?;
    /// let timing = PathTiming::<_, 16, 4>::scurve(&line, &limits)?;
    /// let o = timing.compile_options(&CompileOptions::new().with_tolerance(1e-3));
    /// assert_eq!(o.limits(), Some((1_000.0, 20_000.0)));
    /// assert_eq!(o.axis_acceleration()[..2], [800.0, f64::INFINITY]);
    /// assert_eq!(o.feed_share(), 0.25);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn compile_options(&self, options: &CompileOptions) -> CompileOptions {
        options.completed_by(self.feed_reserve())
    }

    /// Compiles the motion into a path at the plan's [`rate`](Self::rate), with `options`
    /// completed by [`compile_options`](Self::compile_options): the one call that keeps the
    /// feed reserve of the plan and the rate it was planned for. See
    /// [`compile`](crate::compile()).
    ///
    /// # Errors
    /// As [`compile`](crate::compile()).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{CompileOptions, Limits, Path, PathTiming, PlanOptions};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?;
    /// let limits = Limits::<2>::new(100.0, 1_000.0, 20_000.0)?;
    /// let plan = PlanOptions::new().with_rate(2_000.0);
    /// let timing = PathTiming::<_, 16, 4>::plan(&line, &limits, &plan)?;
    /// let path: Path<f32, 2, 64> = timing.compile(&CompileOptions::new())?;
    /// assert_eq!(path.rate(), 2_000.0);
    /// assert_eq!(path.feed_share(), 0.25);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn compile<Num: Number, const A: usize, const P: usize>(
        &self,
        options: &CompileOptions,
    ) -> Result<Path<Num, A, P>, Error> {
        compile(self, self.rate(), options)
    }

    /// [`compile`](Self::compile) into caller-provided storage, in place: see
    /// [`compile_into`](crate::compile_into()). On an error the path is left empty.
    ///
    /// # Errors
    /// As [`compile`](crate::compile()).
    ///
    /// ```
    /// use strak_curves::Bezier;
    /// use strak_trajectory::{CompileOptions, Limits, Path, PathTiming};
    /// let line = Bezier::new([[0.0, 0.0], [30.0, 40.0]])?;
    /// let limits = Limits::<2>::new(100.0, 1_000.0, 20_000.0)?;
    /// let timing = PathTiming::<_, 16, 4>::scurve(&line, &limits)?;
    /// let mut path: Path<f32, 2, 64> = Path::new();
    /// timing.compile_into(&CompileOptions::new(), &mut path)?;
    /// assert_eq!(path.end_position(), [30.0, 40.0]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn compile_into<Num: Number, const A: usize, const P: usize>(
        &self,
        options: &CompileOptions,
        path: &mut Path<Num, A, P>,
    ) -> Result<(), Error> {
        compile_into(self, self.rate(), options, path)
    }
}
