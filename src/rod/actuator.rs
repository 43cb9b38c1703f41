//! Actuators: routing `r(s)` in the body frame and the force laws
//! (TCA, constant tension, linear tendon) with their derivatives.

use std::fmt::Debug;
use std::sync::Arc;

use nalgebra::Vector3;

use crate::error::{finite, human, non_negative, positive, Error, Result};
use crate::tca::Tca;

/// Path of an actuator in the body frame, with exact derivatives in `s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Routing {
    /// Parallel to the centre line at a constant offset `(x, y)` \[m\].
    Straight {
        /// Body-frame x offset \[m\].
        x: f64,
        /// Body-frame y offset \[m\].
        y: f64,
    },
    /// Helix about the centre line: `r = radius (cos(rate s + phase), sin(rate s + phase), 0)`.
    Helix {
        /// Radius \[m\].
        radius: f64,
        /// Angular rate \[rad/m\] (positive: right-handed about +z).
        rate: f64,
        /// Angle at `s = 0` \[rad\].
        phase: f64,
    },
}

impl Routing {
    /// Parallel to the centre line at body-frame offset `(x, y)` \[m\] (finite).
    pub fn straight(x: f64, y: f64) -> Result<Routing> {
        let x = finite("x [m]", x)?;
        let y = finite("y [m]", y)?;
        Ok(Routing::Straight { x, y })
    }

    /// Helix of `radius` \[m\] (>= 0) turning at `rate` \[rad/m\] from angle
    /// `phase` \[rad\] at `s = 0`.
    pub fn helix(radius: f64, rate: f64, phase: f64) -> Result<Routing> {
        let radius = non_negative("radius [m]", radius)?;
        let rate = finite("rate [rad/m]", rate)?;
        let phase = finite("phase [rad]", phase)?;
        Ok(Routing::Helix {
            radius,
            rate,
            phase,
        })
    }

    /// The routing built by constructor `kind` (`"straight"`, `"helix"`) from
    /// the values of [`Routing::parameters`], in order.
    pub fn from_parameters(kind: &str, values: &[f64]) -> Result<Routing> {
        match (kind, values) {
            ("straight", &[x, y]) => Routing::straight(x, y),
            ("helix", &[r, k, p]) => Routing::helix(r, k, p),
            _ => Err(Error::input(
                "kind",
                format!("{kind:?} with {} values is not a routing", values.len()),
            )),
        }
    }

    /// A warning text if the routing's distance from the centre line looks
    /// like millimetres given as metres (above [`crate::error::MM_LOOKING_M`],
    /// 1 m, far beyond any soft robot's section): a valid SI number, so not an
    /// error here (the robot rejects a routing outside its section).
    pub fn units_warning(&self) -> Option<String> {
        let r = self.distance();
        (r.is_finite() && r > crate::error::MM_LOOKING_M).then(|| {
            let what = match self {
                Routing::Straight { .. } => "offset",
                Routing::Helix { .. } => "radius",
            };
            format!(
                "Routing.{}: {what} {} m from the centre line{}",
                self.kind(),
                human(r),
                crate::error::mm_hint(r)
            )
        })
    }

    /// The constructor's name: `"straight"` or `"helix"`.
    pub fn kind(&self) -> &'static str {
        match self {
            Routing::Straight { .. } => "straight",
            Routing::Helix { .. } => "helix",
        }
    }

    /// Distance \[m\] of the routing from the centre line (constant along
    /// either kind).
    pub fn distance(&self) -> f64 {
        match *self {
            Routing::Straight { x, y } => x.hypot(y),
            Routing::Helix { radius, .. } => radius,
        }
    }

    /// The constructor's arguments by name, in order (SI units).
    pub fn parameters(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Routing::Straight { x, y } => vec![("x", x), ("y", y)],
            Routing::Helix {
                radius,
                rate,
                phase,
            } => vec![("radius", radius), ("rate", rate), ("phase", phase)],
        }
    }

    /// `(r, r', r'')` at arc length `s` \[m\].
    #[inline]
    pub fn eval(&self, s: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        match *self {
            Routing::Straight { x, y } => {
                (Vector3::new(x, y, 0.0), Vector3::zeros(), Vector3::zeros())
            }
            Routing::Helix {
                radius,
                rate,
                phase,
            } => {
                let (sn, cs) = (rate * s + phase).sin_cos();
                (
                    Vector3::new(radius * cs, radius * sn, 0.0),
                    Vector3::new(-radius * rate * sn, radius * rate * cs, 0.0),
                    Vector3::new(-radius * rate * rate * cs, -radius * rate * rate * sn, 0.0),
                )
            }
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match *self {
            Routing::Straight { x, y } => {
                finite("routing x [m]", x)?;
                finite("routing y [m]", y)?;
            }
            Routing::Helix {
                radius,
                rate,
                phase,
            } => {
                non_negative("helix radius [m]", radius)?;
                finite("helix rate [rad/m]", rate)?;
                finite("helix phase [rad]", phase)?;
            }
        }
        Ok(())
    }
}

/// The force law of a string-like actuator: tension as a function of the
/// actuator's total elongation and of its actuation input.
///
/// The rod model (eqs 22-33) never looks inside: any law that returns a
/// tension works, which is the paper's point that the equations hold for any
/// string-like actuator. The tension must not decrease as the elongation
/// grows (a string pulls harder the more it is stretched): the
/// multiple-shooting solver's actuator unknown, a coordinate along the
/// law's curve, relies on it ([`crate::solve::law_coordinate`]).
pub trait ForceLaw: Send + Sync + Debug {
    /// Tension \[N\] (positive pulls the anchors together) at total elongation
    /// `elongation` \[m\] (current length minus reference length) and input
    /// `input` (unit in [`ForceLaw::input_name`]).
    fn tension(&self, elongation: f64, input: f64) -> Result<f64>;
    /// Name and unit of the input, e.g. `temperature \[C\]`.
    fn input_name(&self) -> &'static str;
    /// Valid input interval.
    fn input_bounds(&self) -> (f64, f64);
    /// The input at which the actuator is passive (reference state).
    fn reference_input(&self) -> f64;
    /// Error unless `input` is valid.
    fn check_input(&self, input: f64) -> Result<()> {
        let (lo, hi) = self.input_bounds();
        if input.is_finite() && input >= lo && input <= hi {
            Ok(())
        } else {
            Err(out_of_range(self.input_name(), input, (lo, hi)))
        }
    }
    /// Short name of the law.
    fn kind(&self) -> &'static str;
    /// The TCA of a TCA law (its coiled length must fit the anchored span,
    /// its pre-tension sets the length ratio), else `None`.
    fn tca(&self) -> Option<&Tca> {
        None
    }
    /// Inverse law: the elongation \[m\] at which the actuator carries
    /// `tension` \[N\] at `input`, where that is unique. Used only to build
    /// initial guesses (a warm start keeps the tension, a cold start begins at
    /// zero tension), so `None` is always safe.
    fn elongation(&self, _tension: f64, _input: f64) -> Option<f64> {
        None
    }
    /// Tension \[N\] with its derivatives with respect to the elongation
    /// \[N/m\] and to the input [N per input unit], for the exact shooting
    /// Jacobian. The default differences [`ForceLaw::tension`] centrally
    /// (relative step `eps^(1/3)`, error ~1e-10 relative): override it with
    /// the exact derivatives.
    fn tension_derivatives(&self, elongation: f64, input: f64) -> Result<(f64, f64, f64)> {
        let f = self.tension(elongation, input)?;
        let h = f64::EPSILON.cbrt() * elongation.abs().max(1e-6);
        let de = (self.tension(elongation + h, input)? - self.tension(elongation - h, input)?)
            / (2.0 * h);
        Ok((f, de, self.input_slope(elongation, input)?))
    }
    /// Tension \[N\] and its derivative with respect to the elongation
    /// \[N/m\]: the first two of [`ForceLaw::tension_derivatives`], for
    /// callers that hold the input fixed.
    fn tension_and_slope(&self, elongation: f64, input: f64) -> Result<(f64, f64)> {
        let (f, de, _) = self.tension_derivatives(elongation, input)?;
        Ok((f, de))
    }
    /// The elongation interval \[m\] `[a, b]` at `input` across which the
    /// law passes from one smooth piece to another (a TCA's coil contact, a
    /// tendon going slack), `a = b` for a kink; `None` for a smooth law.
    /// The damped Newton method steps to the far end of the interval before
    /// it linearises the law on the other piece ([`crate::solve::nleq`]).
    fn kink(&self, _input: f64) -> Option<(f64, f64)> {
        None
    }
    /// `d tension / d input` by central differences within the input bounds
    /// (step `eps^(1/3) max(1, |input|)`, one-sided at a bound).
    fn input_slope(&self, elongation: f64, input: f64) -> Result<f64> {
        let (lo, hi) = self.input_bounds();
        let h = f64::EPSILON.cbrt() * input.abs().max(1.0);
        let (a, b) = ((input - h).max(lo), (input + h).min(hi));
        if b <= a {
            return Ok(0.0);
        }
        Ok((self.tension(elongation, b)? - self.tension(elongation, a)?) / (b - a))
    }
}

/// The error of an `input` outside a law's valid interval `(lo, hi)`; a
/// side at `f64::MIN` / `f64::MAX` is stated as "finite", not as 309 digits.
fn out_of_range(name: &'static str, input: f64, (lo, hi): (f64, f64)) -> Error {
    let u = match crate::error::split_unit(name).1 {
        Some(u) if u != "-" => format!(" {u}"),
        _ => String::new(),
    };
    let allowed = match (lo > f64::MIN, hi < f64::MAX) {
        (true, true) => format!("{} <= input <= {}{u}", human(lo), human(hi)),
        (true, false) => format!("input >= {}{u} (finite)", human(lo)),
        (false, true) => format!("input <= {}{u} (finite)", human(hi)),
        (false, false) => "a finite input".to_string(),
    };
    Error::param(name, input, allowed)
}

/// The TCA law (eq 13) at the input temperature \[C\]: tension from the TCA's
/// total elongation, with coil contact below zero elongation.
#[derive(Debug, Clone)]
pub struct TcaLaw(pub Tca);

impl ForceLaw for TcaLaw {
    fn tension(&self, elongation: f64, input: f64) -> Result<f64> {
        self.0.at(input)?.tension(elongation)
    }
    fn input_name(&self) -> &'static str {
        "temperature [C]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (self.0.material().t_min(), self.0.material().t_max())
    }
    fn reference_input(&self) -> f64 {
        self.0.material().t_ref()
    }
    fn kind(&self) -> &'static str {
        "tca"
    }
    fn tca(&self) -> Option<&Tca> {
        Some(&self.0)
    }
    /// The default check, naming the TCA's material and its valid range;
    /// a temperature below the range points to the way out (a custom
    /// `Material` valid at that ambient), one that lies in the range once
    /// read as kelvin says temperatures are in Celsius.
    fn check_input(&self, input: f64) -> Result<()> {
        let (lo, hi) = self.input_bounds();
        if input.is_finite() && input >= lo && input <= hi {
            return Ok(());
        }
        let material = self.0.material().name();
        let range = format!(
            "{} <= T <= {} C, the valid range of the TCA's material {material}",
            human(lo),
            human(hi)
        );
        let celsius = input - crate::material::ZERO_CELSIUS_IN_KELVIN;
        let reason = if input.is_finite() && input < lo {
            " (the preset's fits start at 25 C and are not extrapolated). For a colder ambient build \
             Material(..., t_ref=<ambient>, t_min=<ambient>) with coefficients valid there and pass it \
             to Tca(..., material=...)"
                .to_string()
        } else if input.is_finite() && (lo..=hi).contains(&celsius) {
            format!(
                " (temperatures are in Celsius: {} K is {celsius:.2} C)",
                human(input)
            )
        } else if input.is_finite() {
            format!(
                " (above {} C the fibre's fits do not hold; lower the temperature)",
                human(hi)
            )
        } else {
            String::new()
        };
        Err(Error::param(
            self.input_name(),
            input,
            format!("{range}{reason}"),
        ))
    }
    /// Exact in the elongation ([`crate::tca::TcaAt::tension_slope`]) and
    /// in the temperature ([`crate::tca::TcaAt::tension_temperature_slope`]),
    /// from one evaluation of the law at `input`.
    fn tension_derivatives(&self, elongation: f64, input: f64) -> Result<(f64, f64, f64)> {
        let at = self.0.at(input)?;
        Ok((
            at.tension(elongation)?,
            at.tension_slope(elongation)?,
            at.tension_temperature_slope(elongation)?,
        ))
    }
    fn tension_and_slope(&self, elongation: f64, input: f64) -> Result<(f64, f64)> {
        let at = self.0.at(input)?;
        Ok((at.tension(elongation)?, at.tension_slope(elongation)?))
    }
    /// Exact: [`crate::tca::TcaAt::tension_temperature_slope`].
    fn input_slope(&self, elongation: f64, input: f64) -> Result<f64> {
        self.0.at(input)?.tension_temperature_slope(elongation)
    }
    /// Coil contact: the smoothed onset below zero elongation
    /// ([`crate::tca::TcaAt::CONTACT_SMOOTHING`]).
    fn kink(&self, _input: f64) -> Option<(f64, f64)> {
        Some((-crate::tca::TcaAt::CONTACT_SMOOTHING, 0.0))
    }
    fn elongation(&self, tension: f64, input: f64) -> Option<f64> {
        let at = self.0.at(input).ok()?;
        let f0 = at.force(0.0).ok()?;
        if tension >= f0 {
            at.displacement(tension).ok()
        } else {
            at.contact_elongation(tension).ok()
        }
    }
}

/// A tendon pulled with a given tension \[N\] (the input), whatever its elongation.
#[derive(Debug, Clone, Copy)]
pub struct ConstantTension;

impl ForceLaw for ConstantTension {
    fn tension(&self, _elongation: f64, input: f64) -> Result<f64> {
        Ok(input)
    }
    fn input_name(&self) -> &'static str {
        "tension [N]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (0.0, f64::MAX)
    }
    fn reference_input(&self) -> f64 {
        0.0
    }
    fn kind(&self) -> &'static str {
        "tension"
    }
    fn tension_derivatives(&self, _elongation: f64, input: f64) -> Result<(f64, f64, f64)> {
        Ok((input, 0.0, 1.0))
    }
}

/// A linearly elastic tendon of stiffness `k` \[N/m\] under displacement
/// control: the input is the length \[m\] pulled in at the base, the tension is
/// `k (pull + elongation)` and zero when slack.
#[derive(Debug, Clone, Copy)]
pub struct LinearTendon {
    /// Axial stiffness of the tendon \[N/m\].
    pub stiffness: f64,
}

impl ForceLaw for LinearTendon {
    fn tension(&self, elongation: f64, input: f64) -> Result<f64> {
        Ok((self.stiffness * (input + elongation)).max(0.0))
    }
    fn input_name(&self) -> &'static str {
        "pull [m]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (f64::MIN, f64::MAX)
    }
    fn reference_input(&self) -> f64 {
        0.0
    }
    fn kind(&self) -> &'static str {
        "linear_tendon"
    }
    fn tension_derivatives(&self, elongation: f64, input: f64) -> Result<(f64, f64, f64)> {
        let f = self.stiffness * (input + elongation);
        // at the onset (f = 0) the taut side's slope, so that Newton from a
        // zero-tension guess sees the tendon
        Ok(if f >= 0.0 {
            (f, self.stiffness, self.stiffness)
        } else {
            (0.0, 0.0, 0.0)
        })
    }
    /// Slack below the elongation `-input`.
    fn kink(&self, input: f64) -> Option<(f64, f64)> {
        Some((-input, -input))
    }
    fn elongation(&self, tension: f64, input: f64) -> Option<f64> {
        Some(tension.max(0.0) / self.stiffness - input)
    }
}

/// A string-like actuator embedded in the body.
#[derive(Debug, Clone)]
pub struct Actuator {
    /// Path in the body frame.
    pub routing: Routing,
    /// Proximal anchor \[m\] (0: anchored to the base).
    pub s_start: f64,
    /// Distal anchor \[m\] (the body length: anchored at the tip).
    pub s_end: f64,
    /// The paper's length ratio `L_i` (eq 18). `None`: computed pointwise from
    /// the reference configuration, `|nu* + omega* x r + r'|`, which makes the
    /// reference configuration exactly unstrained for any routing and
    /// pre-curvature.
    ///
    /// The actuator's elongation is measured over its whole anchored span, so
    /// a TCA shorter than its span is modelled as the TCA in series with
    /// inextensible leads (knots, crimps, wire) filling the rest of the span:
    /// in the reference shape it is relaxed with its coils touching, and all
    /// of the span's elongation goes into the TCA's law (eqs 2, 13). Its
    /// coiled length only has to fit the span (the robot checks it).
    pub length_ratio: Option<f64>,
    /// Force law.
    pub law: Arc<dyn ForceLaw>,
    /// Tension \[N\] a TCA carries at the reference temperature in the
    /// body's undeformed reference shape; [`crate::rod::Robot::new`] turns it
    /// into `length_ratio`. `None`: not pre-tensioned.
    pub pretension: Option<f64>,
}

impl Actuator {
    /// Distal anchor meaning "the tip": [`crate::rod::Robot::new`] replaces it
    /// with the body length.
    pub const TIP: f64 = f64::INFINITY;

    /// An actuator from `s_start` to `s_end` \[m\] (unchecked; see [`Actuator::anchored`]).
    pub fn new(routing: Routing, s_start: f64, s_end: f64, law: Arc<dyn ForceLaw>) -> Self {
        Actuator {
            routing,
            s_start,
            s_end,
            length_ratio: None,
            law,
            pretension: None,
        }
    }

    /// An actuator anchored from `s_start` \[m\] (>= 0) to `s_end` \[m\] (> 0;
    /// `None`: the tip, [`Actuator::TIP`]) with the paper's constant length
    /// ratio `length_ratio` \[-\] (eq 18; > 0; `None`: pointwise from the
    /// reference shape). The robot checks the anchors against the body.
    pub fn anchored(
        routing: Routing,
        s_start: f64,
        s_end: Option<f64>,
        length_ratio: Option<f64>,
        law: Arc<dyn ForceLaw>,
    ) -> Result<Self> {
        non_negative("s_start [m]", s_start)?;
        if let Some(e) = s_end {
            positive("s_end [m]", e)?;
        }
        if let Some(l) = length_ratio {
            positive("length_ratio [-]", l)?;
        }
        let mut a = Actuator::new(routing, s_start, s_end.unwrap_or(Actuator::TIP), law);
        a.length_ratio = length_ratio;
        Ok(a)
    }

    /// A warning text if an anchor looks like millimetres given as metres
    /// (above 10 m, the body-length threshold of
    /// [`crate::rod::Body::units_warning`]).
    pub fn units_warning(&self) -> Option<String> {
        [("s_start", self.s_start), ("s_end", self.s_end)]
            .into_iter()
            .find(|(_, s)| s.is_finite() && *s > 10.0)
            .map(|(name, s)| {
                format!(
                    "Actuator: {name} = {} m{}",
                    human(s),
                    crate::error::mm_hint(s)
                )
            })
    }

    /// A TCA actuator ([`Actuator::anchored`]) whose input is its temperature
    /// \[C\], optionally installed with `pretension` \[N\] (>= 0) at the
    /// reference temperature (not together with `length_ratio`, which it sets).
    pub fn tca(
        tca: Tca,
        routing: Routing,
        s_start: f64,
        s_end: Option<f64>,
        length_ratio: Option<f64>,
        pretension: Option<f64>,
    ) -> Result<Self> {
        if let Some(f) = pretension {
            if length_ratio.is_some() {
                return Err(Error::input(
                    "pretension_n / length_ratio",
                    "give one of them, not both",
                ));
            }
            let f = non_negative("pretension_n [N]", f)?;
            // the pre-stretch it implies must exist (below the straight-fibre limit)
            tca.displacement(f, tca.material().t_ref())
                .map_err(|e| e.renamed(|n| format!("pretension_n ({n})")))?;
        }
        let law = Arc::new(TcaLaw(tca));
        let mut a = Actuator::anchored(routing, s_start, s_end, length_ratio, law)?;
        a.pretension = pretension;
        Ok(a)
    }
}
