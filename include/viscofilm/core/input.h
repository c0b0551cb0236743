// Helpers to read user input: points, point lists and muparser expressions,
// each checked at parse time with a message naming the parameter.
#ifndef viscofilm_input_h
#define viscofilm_input_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/thread_local_storage.h>

#include <deal.II/lac/vector.h>

#include <viscofilm/core/dimension.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /**
   * A mistake in the user's input. The message names the parameter, what was
   * given and what is accepted; main() prints it without a backtrace.
   */
  DeclException1(ExcInput, std::string, << arg1);

  /// The message of an exception for a user: a deal.II exception's own text
  /// without the file, line and backtrace that what() adds.
  std::string
  error_message(const std::exception &e);

  /// A number as a user wrote it: 0.5, not 0.500000.
  std::string
  to_text(const double value);

  /// Throw ExcInput with @p message unless @p condition holds.
  void
  check_input(const bool condition, const std::string &message);

  /// "x, y" (dim = 2) or "x, y, z" (dim = 3) -> Point<dim>. @p parameter names the
  /// entry in error messages.
  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &parameter);

  /// "x1, y1; x2, y2; ..." (dim coordinates each) -> points (empty text: no points).
  template <int dim>
  std::vector<Point<dim>>
  parse_point_list(const std::string &text, const std::string &parameter);

  /**
   * A vector-valued muparser expression of (x, y, t) read from a parameter
   * file: components separated by ';', constants "name=value, ...". The
   * expression is evaluated once when parsed, so a typo is reported with the
   * parameter's name before the run starts, not in the middle of it.
   */
  template <int dim>
  class ExpressionAt;

  template <int dim>
  class ParsedExpression
  {
  public:
    explicit ParsedExpression(const unsigned int n_components);

    /// Declare the entry @p name (constants: declare_function_constants()).
    static void
    declare(ParameterHandler & prm,
            const std::string &name,
            const std::string &default_expression,
            const std::string &documentation);

    /// Read the expression @p expression with @p constants ("a=1, b=2").
    /// @p parameter is the full parameter path used in messages.
    void
    parse(const std::string &expression,
          const std::string &constants,
          const std::string &parameter);

    /// Component @p component at (@p point, @p time).
    double
    value(const Point<dim> &point, const double time, const unsigned int component = 0) const;

    /// Every component at (@p point, @p time).
    void
    vector_value(const Point<dim> &point, const double time, Vector<double> &values) const;

    /// The expression at @p time as a deal.II Function, for the library's
    /// interpolation and boundary-value calls (it refers to this
    /// expression). Time is an argument of every evaluation: no caller sets
    /// it on a shared object.
    ExpressionAt<dim>
    at(const double time) const;

    const std::string &
    text() const;

  private:
    /// This thread's parser of the expression, made at its first use:
    /// value() and vector_value() set the parser's time (deal.II's parser
    /// keeps one), and the threads of one assembly (WorkStream) evaluate the
    /// same expression, each with a parser of its own and without a lock.
    FunctionParser<dim> &
    thread_parser() const;

    const unsigned int            n_components;
    std::string                   expression;
    std::vector<std::string>      components;
    std::map<std::string, double> constants;
    mutable Threads::ThreadLocalStorage<std::shared_ptr<FunctionParser<dim>>> parsers;
  };


  /// A ParsedExpression at a fixed time: a deal.II Function.
  template <int dim>
  class ExpressionAt : public Function<dim>
  {
  public:
    ExpressionAt(const ParsedExpression<dim> &expression,
                 const unsigned int           n_components,
                 const double                 time);

    double
    value(const Point<dim> &point, const unsigned int component = 0) const override;

    void
    vector_value(const Point<dim> &point, Vector<double> &values) const override;

  private:
    const ParsedExpression<dim> &expression;
  };

  /// "0; 0; …": the zero expression with @p n_components components, the
  /// default of a vector (dim) or stress (n_symmetric_components<dim>) entry.
  std::string
  zero_expression(const unsigned int n_components);

  /// Declare the "Function constants" entry shared by all expressions.
  void
  declare_function_constants(ParameterHandler &prm);
} // namespace viscofilm

#endif
